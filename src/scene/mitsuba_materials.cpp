#include "scene/mitsuba_materials.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "core/error.h"
#include "core/color.h"
#include "core/image_io.h"
#include "scene/mitsuba_importer.h"

namespace fs = std::filesystem;

namespace inet {

const std::vector<Vec3f>& metalPresetF0() {
  // F0 = ((n - 1)^2 + k^2) / ((n + 1)^2 + k^2) of the presets' complex IORs (render/fresnel.h,
  // metalIor), in metalNames() order; tests/scene/mitsuba_importer_test.cpp checks them against
  // fresnelConductor so the two cannot drift apart.
  static const std::vector<Vec3f> f0 = {{0.9667f, 0.8022f, 0.3240f},
                                        {0.9748f, 0.9575f, 0.9063f},
                                        {0.9521f, 0.6197f, 0.5106f},
                                        {0.9280f, 0.9178f, 0.9189f},
                                        {0.6875f, 0.6491f, 0.6870f}};
  return f0;
}

std::string nearestMetal(const Vec3f& f0, Vec3f* tint) {
  const auto& presets = metalPresetF0();
  size_t best = 0;
  for (size_t i = 1; i < presets.size(); ++i)
    if ((presets[i] - f0).squaredNorm() < (presets[best] - f0).squaredNorm()) best = i;
  if (tint) *tint = f0.cwiseQuotient(presets[best]).cwiseMin(1.f).cwiseMax(0.f);
  return metalNames()[best];
}

namespace mitsuba {
namespace {

/// BSDF wrappers nest at most this deep (a <ref> cycle would otherwise never end).
constexpr int kMaxDepth = 16;

/// Mitsuba's conductor names for the metals we have presets of.
const std::map<std::string, std::string>& metalAliases() {
  static const std::map<std::string, std::string> m = {
      {"Ag", "silver"}, {"Al", "aluminium"}, {"Au", "gold"}, {"Cu", "copper"}, {"Cr", "chromium"}};
  return m;
}

float alphaToRoughness(double alpha) {
  return static_cast<float>(std::sqrt(std::clamp(alpha, 0.0, 1.0)));
}

/// Cosine-weighted hemispherical average of the smooth dielectric Fresnel reflectance,
/// Fbar = 2 int_0^1 F(mu) mu dmu, for light arriving from outside (relative index eta >= 1).
double fresnelAverage(double eta) {
  constexpr int kSteps = 4096;
  double sum = 0.0;
  for (int i = 0; i < kSteps; ++i) {
    const double mu = (i + 0.5) / kSteps;
    const double ct = std::sqrt(std::max(0.0, 1.0 - (1.0 - mu * mu) / (eta * eta)));
    const double rs = (mu - eta * ct) / (mu + eta * ct), rp = (eta * mu - ct) / (eta * mu + ct);
    sum += 0.5 * (rs * rs + rp * rp) * mu;
  }
  return 2.0 * sum / kSteps;
}

/// Linear values of an image file: PNG or JPEG (sRGB-decoded) or EXR; nullopt for what the
/// readers here do not take (16-bit PNG).
std::optional<ImageF> readLinear(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
  ImageU8 in;
  try {
    if (ext == ".exr") return readExr(path, {"R", "G", "B"});
    in = ext == ".png" ? readPng8(path) : readJpeg8(path);
  } catch (const InputError&) {  // e.g. a 16-bit PNG, a grey EXR: the caller notes it
    return std::nullopt;
  }
  ImageF out(in.width, in.height, in.channels);
  for (size_t i = 0; i < in.data.size(); ++i) {
    const double c = in.data[i] / 255.0;
    out.data[i] = static_cast<float>(srgbEotf(c));
  }
  if (in.channels == 2 || in.channels == 4)  // alpha is not colour: undo the decoding
    for (size_t i = static_cast<size_t>(in.channels) - 1; i < in.data.size(); i += in.channels)
      out.data[i] = in.data[i] / 255.f;
  return out;
}

/// Mean colour of image `colour`, weighted per texel by image `weight`'s alpha (or its grey
/// value) when one is given and the sizes agree; nullopt when an image cannot be read here.
std::optional<Vec3f> meanColour(const std::string& colour, const std::string& weight) {
  const auto img = readLinear(colour);
  if (!img || img->empty()) return std::nullopt;
  std::optional<ImageF> w;
  if (!weight.empty()) {
    w = readLinear(weight);
    if (!w || w->width != img->width || w->height != img->height) return std::nullopt;
  }
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double total = 0.0;
  for (int y = 0; y < img->height; ++y)
    for (int x = 0; x < img->width; ++x) {
      const float* p = img->pixel(x, y);
      const Eigen::Vector3d c = img->channels >= 3 ? Eigen::Vector3d(p[0], p[1], p[2])
                                                   : Eigen::Vector3d::Constant(p[0]);
      double a = 1.0;
      if (w) a = w->channels == 2 || w->channels == 4 ? w->pixel(x, y)[w->channels - 1]
                                                       : w->pixel(x, y)[0];
      sum += a * c;
      total += a;
    }
  if (!(total > 0.0)) return std::nullopt;
  return (sum / total).cast<float>();
}

struct Converter {
  MaterialContext& ctx;
  const std::string& subject;  // the material's id, for notes

  void note(const std::string& what) { ctx.notes.add(what, subject); }

  /// A colour slot into albedo (+ texture): clamped to [0, 1] as our reflectances must be.
  void albedo(const Plugin& b, const std::string& name, float fallback, Material& m) {
    const Slot s = b.slot(name, Vec3f::Constant(fallback), ctx.notes);
    if (s.texture) {
      texture(*s.texture, m, 0);
      return;
    }
    if (s.value.minCoeff() < 0.f || s.value.maxCoeff() > 1.f)
      note(fmt::format("{} '{}' outside [0, 1] clamped", b.type(), name));
    m.albedo = s.value.cwiseMax(0.f).cwiseMin(1.f);
  }

  /// A texture in a reflectance slot: a bitmap (optionally scaled) becomes the albedo map.
  void texture(const Plugin& t, Material& m, int depth) {
    const std::string type = t.type();
    if (type == "scale") {  // Mitsuba 0.6: a texture times a factor; our albedo multiplies
      if (depth > kMaxDepth) t.fail("textures nest too deeply (does a <ref> point at itself?)");
      const double f = t.number("scale", 1.0);
      auto inner = t.children("texture");
      if (inner.empty()) t.fail("a scale texture needs a nested texture");
      texture(inner.front(), m, depth + 1);
      m.albedo = (m.albedo * static_cast<float>(f)).cwiseMax(0.f).cwiseMin(1.f);
      return;
    }
    if (type != "bitmap") {
      Vec3f mean = Vec3f::Constant(0.5f);
      if (type == "checkerboard")
        mean = 0.5f * (t.slot("color0", Vec3f::Constant(0.4f), ctx.notes).value +
                       t.slot("color1", Vec3f::Constant(0.2f), ctx.notes).value);
      note(fmt::format("texture type '{}' not supported: its mean colour is used", type));
      m.albedo = mean.cwiseMax(0.f).cwiseMin(1.f);
      return;
    }
    m.albedo_texture = bitmapFile(t, ctx, subject);
    m.albedo = m.albedo_texture.empty() ? Vec3f::Constant(0.5f) : Vec3f::Ones();
    m.uv_scale = uvScale(t);
    if (t.boolean("raw", false)) note("bitmap raw=true (linear) colour read as sRGB");
    if (t.has("gamma") && t.number("gamma", -1.0) != -1.0)
      note("bitmap gamma override ignored (8-bit images are read as sRGB, EXR as linear)");
  }

  Vec2f uvScale(const Plugin& t) {
    Vec2f s(static_cast<float>(t.number("uscale", 1.0)), static_cast<float>(t.number("vscale", 1.0)));
    if (t.has("to_uv")) {
      const Mat4 m = t.transform("to_uv");
      if (m(0, 1) != 0 || m(1, 0) != 0 || m(0, 3) != 0 || m(1, 3) != 0)
        note("bitmap to_uv with rotation or offset: only its scale is kept");
      s = s.cwiseProduct(Vec2f(static_cast<float>(m.block<2, 1>(0, 0).norm()),
                               static_cast<float>(m.block<2, 1>(0, 1).norm())));
    }
    if (!(s.allFinite() && s.minCoeff() > 0.f)) t.fail("uscale/vscale must be > 0");
    return s;
  }

  /// Mitsuba's alpha (a number or a texture) as our roughness.
  void roughness(const Plugin& b, double fallback, Material& m) {
    const std::string dist = b.string("distribution", "beckmann");
    if (dist != "ggx") note(fmt::format("'{}' microfacets rendered as GGX with the same alpha", dist));
    if (b.has("alpha_u") || b.has("alpha_v")) {
      const double au = b.number("alpha_u", fallback), av = b.number("alpha_v", fallback);
      if (au != av) note("anisotropic alpha_u/alpha_v: their geometric mean is used");
      m.roughness = alphaToRoughness(std::sqrt(std::max(au, 0.0) * std::max(av, 0.0)));
      return;
    }
    const Slot s = b.slot("alpha", Vec3f::Constant(static_cast<float>(fallback)), ctx.notes);
    if (s.texture) {
      m.roughness = 1.f;
      if (s.texture->type() == "bitmap") {
        m.roughness_texture = bitmapFile(*s.texture, ctx, subject);
        note("alpha texture read as a roughness map (so alpha = texel^2, not texel)");
      } else {
        m.roughness = alphaToRoughness(fallback);
        note("alpha texture that is not a bitmap ignored");
      }
      return;
    }
    if (s.value.x() > 1.f) note("alpha above 1 clamped to 1");
    m.roughness = alphaToRoughness(s.value.x());
  }

  /// One index of refraction property: a number or one of Mitsuba's names ("bk7", "water").
  double iorValue(const Plugin& b, const std::string& name, double fallback) {
    if (b.kind(name) == "string") {
      const std::string text = b.string(name, "");
      auto v = namedIor(text);
      if (!v)
        b.doc().fail(b.node(), fmt::format("unknown {} '{}' (valid: a number or {})", name, text,
                                           namedIorList()));
      return *v;
    }
    return b.number(name, fallback);
  }

  /// int_ior / ext_ior as one relative index in our range [1, 4].
  float ior(const Plugin& b, double int_default, double ext_default) {
    if (b.has("eta")) return clampIor(b.number("eta", int_default));
    const double in = iorValue(b, "int_ior", int_default), out = iorValue(b, "ext_ior", ext_default);
    if (!(in > 0 && out > 0)) b.fail("int_ior and ext_ior must be > 0");
    double eta = in / out;
    if (eta < 1.0) {
      note("int_ior below ext_ior (a bubble) inverted: our dielectrics have the dense side inside");
      eta = 1.0 / eta;
    }
    return clampIor(eta);
  }

  float clampIor(double eta) {
    if (!(eta >= 1.0 && eta <= 4.0)) note("relative index of refraction clamped to [1, 4]");
    return static_cast<float>(std::clamp(eta, 1.0, 4.0));
  }

  void conductor(const Plugin& b, Material& m) {
    m.type = MaterialType::Conductor;
    Vec3f tint = Vec3f::Ones();
    if (b.has("eta") || b.has("k")) {
      const Slot eta = b.slot("eta", Vec3f::Zero(), ctx.notes);
      const Slot k = b.slot("k", Vec3f::Ones(), ctx.notes);
      if (eta.texture || k.texture) b.fail("eta and k must be colours, not textures");
      const Vec3f n = eta.value, kk = k.value;
      const Vec3f f0 = ((n.array() - 1).square() + kk.array().square()) /
                       ((n.array() + 1).square() + kk.array().square());
      m.metal = nearestMetal(f0, &tint);
      const Vec3f preset = metalPresetF0()[std::find(metalNames().begin(), metalNames().end(),
                                                     m.metal) -
                                           metalNames().begin()];
      if ((preset - f0).cwiseAbs().maxCoeff() > 0.01f)
        note(fmt::format("conductor eta/k: nearest preset '{}', tinted to its F0", m.metal));
      else
        tint = Vec3f::Ones();
    } else {
      const std::string def = b.doc().majorVersion() == 0 ? "Cu" : "none";
      const std::string name = b.string("material", def);
      auto it = metalAliases().find(name);
      if (it != metalAliases().end()) {
        m.metal = it->second;
      } else if (name == "none") {
        m.metal = "silver";
        note("conductor 'none' (a perfect mirror) rendered as silver (F0 0.91-0.97)");
      } else {
        m.metal = "aluminium";
        note(fmt::format("conductor material '{}' has no preset: aluminium used", name));
      }
    }
    const Slot spec = b.slot("specular_reflectance", Vec3f::Ones(), ctx.notes);
    if (spec.texture) note("conductor specular_reflectance texture ignored");
    m.albedo = tint.cwiseProduct(spec.texture ? Vec3f::Ones() : spec.value).cwiseMax(0.f).cwiseMin(1.f);
    if (b.type() == "roughconductor") roughness(b, 0.1, m);
  }

  void plastic(const Plugin& b, Material& m) {
    m.type = MaterialType::Plastic;
    albedo(b, "diffuse_reflectance", 0.5f, m);
    const Slot spec = b.slot("specular_reflectance", Vec3f::Ones(), ctx.notes);
    if (spec.texture || spec.value != Vec3f::Ones())
      note("plastic specular_reflectance other than 1 ignored (the coating follows its ior)");
    m.ior = ior(b, 1.49, 1.000277);
    if (b.boolean("nonlinear", false)) nonlinear(m);
    if (b.type() == "roughplastic") roughness(b, 0.1, m);
  }

  /// Mitsuba's nonlinear=true plastic: light scattered back down by the coating's inside meets
  /// the base again, so its diffuse lobe is R / (1 - R Fdr) where the linear one (ours) is
  /// R / (1 - Fdr), Fdr the coating's internal diffuse reflectance. A base colour R' =
  /// R (1 - Fdr) / (1 - R Fdr) gives the same lobe: exact for a constant colour; a texture is
  /// scaled by the factor of its mean colour.
  void nonlinear(Material& m) {
    const double eta = m.ior;
    const double fdr = 1.0 - (1.0 - fresnelAverage(eta)) / (eta * eta);
    Vec3f r = m.albedo;
    if (!m.albedo_texture.empty()) {
      const auto mean = ctx.read_files ? meanColour(m.albedo_texture.path, "") : std::nullopt;
      if (!mean) {
        note("plastic nonlinear=true on an unread texture: its darkening is left out");
        return;
      }
      r = r.cwiseProduct(*mean);
    }
    const Vec3f factor = (1.0 - fdr) / (1.0 - r.array().cast<double>() * fdr).cast<float>();
    m.albedo = m.albedo.cwiseProduct(factor).cwiseMin(1.f);
    note(m.albedo_texture.empty()
             ? "plastic nonlinear=true: base colour R taken as R (1 - Fdr) / (1 - R Fdr)"
             : "plastic nonlinear=true on a texture: scaled by the factor of its mean colour");
  }

  void dielectric(const Plugin& b, Material& m) {
    const std::string type = b.type();
    m.type = type == "thindielectric" ? MaterialType::ThinDielectric : MaterialType::Dielectric;
    m.ior = ior(b, 1.5046, 1.000277);
    const Slot r = b.slot("specular_reflectance", Vec3f::Ones(), ctx.notes);
    if (r.texture || r.value != Vec3f::Ones())
      note("dielectric specular_reflectance other than 1 ignored");
    const Slot t = b.slot("specular_transmittance", Vec3f::Ones(), ctx.notes);
    if (t.texture) note("dielectric specular_transmittance texture ignored");
    m.transmittance = t.texture ? Vec3f::Ones() : Vec3f(t.value.cwiseMax(0.f).cwiseMin(1.f));
    if (type == "roughdielectric") roughness(b, 0.1, m);
  }

  void principled(const Plugin& b, Material& m) {
    albedo(b, "base_color", 0.5f, m);
    const double rough = b.number("roughness", 0.5), metallic = b.number("metallic", 0.0);
    const double trans = b.number("spec_trans", 0.0);
    m.roughness = static_cast<float>(std::clamp(rough, 0.0, 1.0));
    note("principled BSDF mapped to its dominant family (plastic, conductor or dielectric)");
    if (trans > 0.5) {
      m.type = MaterialType::Dielectric;
      m.ior = clampIor(b.number("eta", 1.5));
    } else if (metallic >= 0.5) {
      m.type = MaterialType::Conductor;
      Vec3f tint;
      m.metal = nearestMetal(m.albedo, &tint);
      m.albedo = tint;
      m.albedo_texture = {};
    } else {
      m.type = MaterialType::Plastic;
      m.ior = clampIor(b.number("eta", 1.5));
    }
  }

  void leaf(const Plugin& b, Material& m) {
    const std::string type = b.type();
    if (type == "diffuse" || type == "roughdiffuse") {
      m.type = MaterialType::Lambertian;
      albedo(b, "reflectance", 0.5f, m);
      if (type == "roughdiffuse") note("roughdiffuse (Oren-Nayar) rendered as Lambertian");
    } else if (type == "plastic" || type == "roughplastic") {
      plastic(b, m);
    } else if (type == "conductor" || type == "roughconductor") {
      conductor(b, m);
    } else if (type == "dielectric" || type == "roughdielectric" || type == "thindielectric") {
      dielectric(b, m);
    } else if (type == "difftrans") {
      m.type = MaterialType::Translucent;
      m.albedo = Vec3f::Zero();
      const Slot t = b.slot("transmittance", Vec3f::Constant(0.5f), ctx.notes);
      if (t.texture) note("difftrans transmittance texture ignored");
      m.transmittance = t.texture ? Vec3f::Constant(0.5f) : Vec3f(t.value.cwiseMax(0.f).cwiseMin(1.f));
    } else if (type == "principled" || type == "principledthin") {
      principled(b, m);
    } else if (type == "phong" || type == "ward") {
      m.type = MaterialType::Plastic;
      albedo(b, "diffuse_reflectance", 0.5f, m);
      const double alpha = type == "phong" ? std::sqrt(2.0 / (b.number("exponent", 30.0) + 2.0))
                                           : b.number("alpha_u", 0.1);
      b.ignore("alpha_v");
      b.ignore("specular_reflectance");
      m.roughness = alphaToRoughness(alpha);
      note(fmt::format("{} BSDF approximated by a rough plastic", type));
    } else {
      m.type = MaterialType::Lambertian;
      m.albedo = Vec3f::Constant(0.5f);
      note(fmt::format("unsupported BSDF type '{}': grey diffuse (0.5) used", type));
      return;
    }
    for (const std::string& p : b.unused()) note(fmt::format("{} property '{}' ignored", type, p));
  }

  /// Unwraps twosided, mask, bump and the like down to one leaf BSDF.
  void convert(const Plugin& b, Material& m, int depth, bool& two_sided, bool& null) {
    if (depth > kMaxDepth) b.fail("BSDFs nest too deeply (does a <ref> point at its own parent?)");
    const std::string type = b.type();
    if (type.empty()) b.fail("a <bsdf> needs a type attribute");
    auto inner = [&](size_t want) {
      auto kids = b.children("bsdf");
      if (kids.size() < want) b.fail(fmt::format("a {} BSDF needs {} nested BSDF(s)", type, want));
      return kids;
    };
    if (type == "null") {
      null = true;
    } else if (type == "twosided") {
      auto kids = inner(1);
      if (kids.size() > 1) note("twosided with a different back BSDF: the front one is used");
      two_sided = true;
      convert(kids.front(), m, depth + 1, two_sided, null);
    } else if (type == "mask") {
      const Slot opacity = b.slot("opacity", Vec3f::Constant(0.5f), ctx.notes);
      convert(inner(1).front(), m, depth + 1, two_sided, null);
      mask(opacity, m);
    } else if (type == "bumpmap" || type == "bump") {
      b.children("texture");
      for (const char* p : {"bumpmap", "texture", "scale"}) b.ignore(p);
      note("bump map ignored (only normal maps are supported)");
      convert(inner(1).front(), m, depth + 1, two_sided, null);
    } else if (type == "normalmap") {
      const Slot n = b.slot("normalmap", Vec3f::Zero(), ctx.notes);
      convert(inner(1).front(), m, depth + 1, two_sided, null);
      if (n.texture && n.texture->type() == "bitmap") m.normal_texture = bitmapFile(*n.texture, ctx, subject);
      else note("normalmap without a bitmap ignored");
    } else if (type == "coating" || type == "roughcoating") {
      convert(inner(1).front(), m, depth + 1, two_sided, null);
      if (m.type == MaterialType::Lambertian) {  // a coated diffuse is exactly our plastic
        m.type = MaterialType::Plastic;
        m.ior = ior(b, 1.49, 1.000277);
        m.roughness = 0.f;
        if (type == "roughcoating") roughness(b, 0.1, m);
      } else {
        note("coating over a BSDF that is not diffuse ignored");
      }
    } else if (type == "blendbsdf" || type == "mixturebsdf") {
      auto kids = inner(2);
      size_t pick = 0;
      if (type == "blendbsdf") {
        pick = b.number("weight", 0.5) > 0.5 ? 1 : 0;
      } else {
        b.ignore("weights");
      }
      note(fmt::format("{}: only its main component is used", type));
      convert(kids[std::min(pick, kids.size() - 1)], m, depth + 1, two_sided, null);
    } else {
      leafOf(b, m, two_sided);
    }
  }

  /// No cut-outs here: a masked surface is opaque. Where the opacity is an image and the colour
  /// a texture, the colour becomes the mean over the opaque texels, so that leaves are green
  /// rather than the colour of their texture's transparent background.
  void mask(const Slot& opacity, Material& m) {
    if (opacity.texture && opacity.texture->type() == "bitmap" && !m.albedo_texture.empty() &&
        ctx.read_files) {
      const TextureRef weights = bitmapFile(*opacity.texture, ctx, subject);
      if (auto mean = weights.empty() ? std::nullopt : meanColour(m.albedo_texture.path, weights.path)) {
        m.albedo = m.albedo.cwiseProduct(*mean).cwiseMax(0.f).cwiseMin(1.f);
        m.albedo_texture = {};
        note("mask (opacity cut-out) not supported: opaque, coloured with the mean of the "
             "opaque texels");
        return;
      }
    }
    note("mask (opacity cut-out) not supported: the surface is opaque");
  }

  void leafOf(const Plugin& b, Material& m, bool two_sided) {
    leaf(b, m);
    const bool reflective = m.type == MaterialType::Lambertian || m.type == MaterialType::Plastic ||
                            m.type == MaterialType::Conductor;
    if (reflective && !two_sided)
      note("one-sided BSDF rendered two-sided (Mitsuba's back side is black)");
  }
};

}  // namespace

std::string MaterialContext::uniqueId(const std::string& base) {
  std::string id = base.empty() ? "material" : base;
  for (int k = 2; ids.count(id); ++k) id = fmt::format("{}_{}", base, k);
  ids.insert(id);
  return id;
}

int materialOf(const Plugin& bsdf, MaterialContext& ctx, const std::string& owner) {
  const void* key = bsdf.node().internal_object();
  if (auto it = ctx.by_element.find(key); it != ctx.by_element.end()) return it->second;
  Material m;
  m.id = ctx.uniqueId(bsdf.id().empty() ? owner + "_bsdf" : bsdf.id());
  bool two_sided = false, null = false;
  Converter conv{ctx, m.id};
  conv.convert(bsdf, m, 0, two_sided, null);
  int index = -1;
  if (null) {
    ctx.notes.add("null BSDF (invisible surface): its shapes are left out", m.id);
  } else {
    ctx.scene.materials.push_back(std::move(m));
    index = static_cast<int>(ctx.scene.materials.size()) - 1;
  }
  ctx.by_element[key] = index;
  return index;
}

int defaultMaterial(MaterialContext& ctx) {
  if (ctx.default_material < 0) {
    Material m;
    m.id = ctx.uniqueId("mitsuba_default");
    m.albedo = Vec3f::Constant(0.5f);
    ctx.scene.materials.push_back(std::move(m));
    ctx.default_material = static_cast<int>(ctx.scene.materials.size()) - 1;
  }
  return ctx.default_material;
}

TextureRef bitmapFile(const Plugin& texture, MaterialContext& ctx, const std::string& subject) {
  const std::string file = texture.string("filename", "");
  if (file.empty()) texture.fail("a bitmap texture needs a filename");
  for (const char* p : {"filter_type", "wrap_mode", "wrap_mode_u", "wrap_mode_v", "cache",
                        "max_anisotropy", "channel"})
    texture.ignore(p);
  const fs::path path = fs::path(file).is_absolute()
                            ? fs::path(file)
                            : fs::path(texture.doc().folderOf(texture.node())) / file;
  std::error_code ec;
  if (ctx.read_files && !fs::is_regular_file(path, ec))
    texture.fail(fmt::format("'{}': file not found", path.string()));
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
  if (ext != ".png" && ext != ".jpg" && ext != ".jpeg" && ext != ".exr") {
    ctx.notes.add(fmt::format("texture format '{}' not readable (PNG, JPEG, EXR are): ignored", ext),
                  subject);
    return {};
  }
  TextureRef ref;
  ref.file = ref.path = path.lexically_normal().string();
  return ref;
}

}  // namespace mitsuba
}  // namespace inet
