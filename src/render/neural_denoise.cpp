#include "render/neural_denoise.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/rng.h"
#include "core/weights_file.h"
#include "render/denoise.h"

namespace inet {

namespace {

constexpr char kMagic[8] = {'I', 'N', 'E', 'T', 'D', 'N', 'S', 'R'};
constexpr uint32_t kFormatVersion = 1;
constexpr uint32_t kDenoiserRngTag = 0x444e5352;  // "DNSR"
constexpr int kMaxChannels = 256;
constexpr float kLogitBound = 8.f;  // logits are soft-bounded to (-8, 8): see the header

template <typename Body>
void forEachRow(int height, const Body& body) {
  tbb::parallel_for(tbb::blocked_range<int>(0, height, 2), [&](const auto& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y) body(y);
  });
}

/// A convolution with its weights reordered for the inner loop: [ky][kx][in][out], so the
/// innermost loop runs over output channels and vectorises.
struct PackedConv {
  int in = 0, out = 0, k = 3;
  std::vector<float> w, b;
};

PackedConv pack(const ConvLayer& c) {
  PackedConv p{c.in, c.out, c.k, std::vector<float>(c.weight.size()), c.bias};
  for (int o = 0; o < c.out; ++o)
    for (int i = 0; i < c.in; ++i)
      for (int ky = 0; ky < c.k; ++ky)
        for (int kx = 0; kx < c.k; ++kx)
          p.w[((static_cast<size_t>(ky) * c.k + kx) * c.in + i) * c.out + o] =
              c.weight[((static_cast<size_t>(o) * c.in + i) * c.k + ky) * c.k + kx];
  return p;
}

/// out = act(conv(in)) with zero padding (taps outside the image are skipped, which adds the
/// same zeros). Each output value sums its taps in one fixed order.
ImageF convolve(const ImageF& in, const PackedConv& p, bool activate, float leak) {
  INET_CHECK(in.channels == p.in);
  ImageF out(in.width, in.height, p.out);
  const int r = p.k / 2;
  forEachRow(in.height, [&](int y) {
    float acc[kMaxChannels];
    for (int x = 0; x < in.width; ++x) {
      for (int o = 0; o < p.out; ++o) acc[o] = p.b[o];
      for (int ky = 0; ky < p.k; ++ky) {
        const int sy = y + ky - r;
        if (sy < 0 || sy >= in.height) continue;
        for (int kx = 0; kx < p.k; ++kx) {
          const int sx = x + kx - r;
          if (sx < 0 || sx >= in.width) continue;
          const float* src = in.pixel(sx, sy);
          const float* w = p.w.data() + (static_cast<size_t>(ky) * p.k + kx) * p.in * p.out;
          for (int i = 0; i < p.in; ++i) {
            const float v = src[i];
            const float* wi = w + static_cast<size_t>(i) * p.out;
            for (int o = 0; o < p.out; ++o) acc[o] += v * wi[o];
          }
        }
      }
      float* dst = out.pixel(x, y);
      for (int o = 0; o < p.out; ++o)
        dst[o] = activate && acc[o] < 0.f ? leak * acc[o] : acc[o];
    }
  });
  return out;
}

ImageF avgPool2(const ImageF& in) {
  ImageF out(in.width / 2, in.height / 2, in.channels);
  const int c = in.channels;
  forEachRow(out.height, [&](int y) {
    for (int x = 0; x < out.width; ++x) {
      const float* a = in.pixel(2 * x, 2 * y);
      const float* b = in.pixel(2 * x + 1, 2 * y);
      const float* d = in.pixel(2 * x, 2 * y + 1);
      const float* e = in.pixel(2 * x + 1, 2 * y + 1);
      float* o = out.pixel(x, y);
      for (int i = 0; i < c; ++i) o[i] = ((a[i] + b[i]) + (d[i] + e[i])) * 0.25f;
    }
  });
  return out;
}

/// concat(up2(coarse), fine) along channels, at fine's size.
ImageF upConcat(const ImageF& coarse, const ImageF& fine) {
  INET_CHECK(coarse.width * 2 == fine.width && coarse.height * 2 == fine.height);
  ImageF out(fine.width, fine.height, coarse.channels + fine.channels);
  forEachRow(fine.height, [&](int y) {
    for (int x = 0; x < fine.width; ++x) {
      float* o = out.pixel(x, y);
      std::memcpy(o, coarse.pixel(x / 2, y / 2), sizeof(float) * coarse.channels);
      std::memcpy(o + coarse.channels, fine.pixel(x, y), sizeof(float) * fine.channels);
    }
  });
  return out;
}

void checkSameSize(const ImageF& a, const ImageF& ref, int channels, const char* name) {
  INET_CHECK_MSG(a.width == ref.width && a.height == ref.height && a.channels == channels,
                 std::string("neural denoiser: ") + name + " has the wrong size or channels");
}

bool finite3(const float* p) {
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

}  // namespace

void NeuralDenoiserConfig::validate(const std::string& where) const {
  if (channels.empty() || channels.size() > 6)
    throw InputError(where, "config.channels", "needs 1 to 6 levels");
  for (int c : channels)
    if (c < 1 || c > kMaxChannels)
      throw InputError(where, "config.channels", "each level needs 1 to 256 channels");
  if (!(leak >= 0.f && leak < 1.f)) throw InputError(where, "config.leak", "must be in [0, 1)");
  if (!(albedo_epsilon > 0.f && albedo_epsilon <= 1.f))
    throw InputError(where, "config.albedo_epsilon", "must be in (0, 1]");
}

std::vector<ConvLayer> NeuralDenoiser::shapes(const NeuralDenoiserConfig& config) {
  std::vector<ConvLayer> s;
  auto add = [&](int in, int out, int k) {
    ConvLayer c;
    c.in = in;
    c.out = out;
    c.k = k;
    s.push_back(c);
  };
  const auto& C = config.channels;
  const int L = static_cast<int>(C.size());
  for (int l = 0; l < L; ++l) {
    add(l == 0 ? kDenoiserFeatureCount : C[l - 1], C[l], 3);
    add(C[l], C[l], 3);
  }
  for (int l = L - 2; l >= 0; --l) add(C[l + 1] + C[l], C[l], 3);
  add(C[0], kDenoiserCandidates, 1);
  return s;
}

NeuralDenoiser NeuralDenoiser::random(const NeuralDenoiserConfig& config, uint64_t seed) {
  config.validate("NeuralDenoiser::random");
  NeuralDenoiser net;
  net.config = config;
  net.convs = shapes(config);
  uint32_t index = 0;
  for (ConvLayer& c : net.convs) {
    const double fan_in = static_cast<double>(c.in) * c.k * c.k;
    const double gain = std::sqrt(2.0 / (1.0 + double(config.leak) * config.leak));
    const double bound = gain * std::sqrt(3.0 / fan_in);
    CounterRng rng(seed, RngStream::Sensor, kDenoiserRngTag, index++, 0);
    c.weight.resize(static_cast<size_t>(c.out) * c.in * c.k * c.k);
    for (float& w : c.weight) w = static_cast<float>(rng.uniformDouble(-bound, bound));
    c.bias.assign(c.out, 0.f);
  }
  // the head starts at zero: equal weights for every candidate, far from softmax saturation
  std::fill(net.convs.back().weight.begin(), net.convs.back().weight.end(), 0.f);
  return net;
}

size_t NeuralDenoiser::parameterCount() const {
  size_t n = 0;
  for (const ConvLayer& c : convs) n += c.weight.size() + c.bias.size();
  return n;
}

std::vector<ImageF> denoiserCandidates(const ImageF& reflected, const ImageF& variance,
                                       const ImageF& footprint_albedo, const ImageF& normal,
                                       const ImageF& depth, float albedo_epsilon) {
  const float eps = albedo_epsilon;
  std::vector<ImageF> c;
  c.reserve(kDenoiserCandidates);
  auto demodulated = [&](const ImageF& r) {
    ImageF e(r.width, r.height, 3);
    for (size_t i = 0; i < e.data.size(); ++i)
      e.data[i] = std::max(r.data[i], 0.f) / std::max(footprint_albedo.data[i], eps);
    return e;
  };
  c.push_back(demodulated(reflected));
  // one à-trous run per colour weight, stopped at the levels the candidates need
  auto filtered = [&](float sigma_color, const std::vector<int>& levels) {
    DenoiseOptions o;
    o.sigma_color = sigma_color;
    o.albedo_epsilon = eps;
    for (const ImageF& f :
         denoiseLevels(reflected, footprint_albedo, normal, depth, &variance, o, levels))
      c.push_back(demodulated(f));
  };
  filtered(2.f, {3});
  filtered(4.f, {5});
  filtered(1e4f, {3, 5, 7});
  return c;
}

DenoiserInput denoiserFeatures(const ImageF& reflected, const ImageF& variance,
                               const ImageF& footprint_albedo, const ImageF& albedo,
                               const ImageF& normal, const ImageF& depth, float albedo_epsilon) {
  checkSameSize(reflected, reflected, 3, "reflected");
  checkSameSize(variance, reflected, 3, "variance");
  checkSameSize(footprint_albedo, reflected, 3, "footprint albedo");
  checkSameSize(albedo, reflected, 3, "albedo");
  checkSameSize(normal, reflected, 3, "normal");
  checkSameSize(depth, reflected, 1, "depth");
  const size_t n = reflected.pixelCount();
  const float eps = albedo_epsilon;
  DenoiserInput in;
  in.features = ImageF(reflected.width, reflected.height, kDenoiserFeatureCount);
  in.valid.assign(n, 0);
  // one pass in pixel order for the frame's two means (double, fixed order: deterministic)
  double log_lum = 0, log_z = 0;
  size_t count = 0;
  for (size_t i = 0; i < n; ++i) {
    const float* nn = &normal.data[3 * i];
    const float z = depth.data[i];
    const float* r = &reflected.data[3 * i];
    if (!(z > 0.f) || !std::isfinite(z) || (nn[0] == 0.f && nn[1] == 0.f && nn[2] == 0.f) ||
        !finite3(r) || !finite3(nn))
      continue;
    in.valid[i] = 1;
    const float* a = &footprint_albedo.data[3 * i];
    const double lum = 0.2126 * std::max(r[0], 0.f) / std::max(a[0], eps) +
                       0.7152 * std::max(r[1], 0.f) / std::max(a[1], eps) +
                       0.0722 * std::max(r[2], 0.f) / std::max(a[2], eps);
    log_lum += std::log(std::max(lum, 1e-6));
    log_z += std::log(static_cast<double>(z));
    ++count;
  }
  in.candidates.assign(kDenoiserCandidates, ImageF(reflected.width, reflected.height, 3));
  if (count == 0) return in;
  in.scale = static_cast<float>(std::exp(log_lum / static_cast<double>(count)));
  const float inv_m = 1.f / in.scale;
  const float mean_log_z = static_cast<float>(log_z / static_cast<double>(count));
  // the filters see surface pixels only: others are copied through by denoise() anyway, and
  // a non-finite colour must not reach a neighbour
  ImageF clean = reflected;
  for (size_t i = 0; i < n; ++i)
    if (!in.valid[i]) clean.data[3 * i] = clean.data[3 * i + 1] = clean.data[3 * i + 2] = 0.f;
  const std::vector<ImageF> cand =
      denoiserCandidates(clean, variance, footprint_albedo, normal, depth, eps);
  forEachRow(reflected.height, [&](int y) {
    for (size_t i = static_cast<size_t>(y) * reflected.width;
         i < static_cast<size_t>(y + 1) * reflected.width; ++i) {
      if (!in.valid[i]) continue;
      float* f = &in.features.data[i * kDenoiserFeatureCount];
      for (int c = 0; c < 3; ++c) {
        const float a = std::max(footprint_albedo.data[3 * i + c], eps);
        float v = variance.data[3 * i + c];
        v = std::isfinite(v) && v > 0.f ? v : 0.f;
        f[3 + c] = std::log1p(std::sqrt(v) / a * inv_m);
        f[6 + c] = albedo.data[3 * i + c];
        f[9 + c] = normal.data[3 * i + c];
        for (int k = 0; k < kDenoiserCandidates; ++k) {
          float e = cand[k].data[3 * i + c] * inv_m;
          e = std::isfinite(e) ? std::max(e, 0.f) : 0.f;
          in.candidates[k].data[3 * i + c] = e;
          const float l = std::log1p(e);
          if (k == 0) {
            f[c] = l;
          } else {
            f[13 + 3 * (k - 1) + c] = l;
          }
        }
      }
      f[12] = std::log(depth.data[i]) - mean_log_z;
    }
  });
  return in;
}

ImageF runNeuralDenoiser(const NeuralDenoiser& net, const ImageF& features) {
  INET_CHECK(features.channels == kDenoiserFeatureCount);
  const auto& C = net.config.channels;
  const int L = static_cast<int>(C.size());
  INET_CHECK_MSG(net.convs.size() == NeuralDenoiser::shapes(net.config).size(),
                 "neural denoiser: weights do not match the config");
  const int m = 1 << (L - 1);
  const int W = (features.width + m - 1) / m * m, H = (features.height + m - 1) / m * m;
  ImageF x(W, H, kDenoiserFeatureCount);  // zero-padded right and bottom
  for (int y = 0; y < features.height; ++y)
    std::memcpy(x.pixel(0, y), features.pixel(0, y),
                sizeof(float) * features.width * kDenoiserFeatureCount);
  std::vector<PackedConv> p;
  for (const ConvLayer& c : net.convs) p.push_back(pack(c));
  const float leak = net.config.leak;
  std::vector<ImageF> enc(L);
  size_t k = 0;
  for (int l = 0; l < L; ++l) {
    ImageF h = convolve(l == 0 ? x : avgPool2(enc[l - 1]), p[k++], true, leak);
    enc[l] = convolve(h, p[k++], true, leak);
  }
  ImageF dec = std::move(enc[L - 1]);
  for (int l = L - 2; l >= 0; --l) dec = convolve(upConcat(dec, enc[l]), p[k++], true, leak);
  const ImageF out = convolve(dec, p[k++], false, leak);
  const int K = out.channels;
  ImageF cropped(features.width, features.height, K);
  for (int y = 0; y < features.height; ++y)
    std::memcpy(cropped.pixel(0, y), out.pixel(0, y), sizeof(float) * K * features.width);
  return cropped;
}

ImageF neuralDenoise(const NeuralDenoiser& net, const ImageF& reflected, const ImageF& variance,
                     const ImageF& footprint_albedo, const ImageF& albedo, const ImageF& normal,
                     const ImageF& depth) {
  const float eps = net.config.albedo_epsilon;
  const DenoiserInput in =
      denoiserFeatures(reflected, variance, footprint_albedo, albedo, normal, depth, eps);
  ImageF result = reflected;
  if (std::find(in.valid.begin(), in.valid.end(), 1) == in.valid.end()) return result;
  const ImageF logits = runNeuralDenoiser(net, in.features);
  const size_t n = reflected.pixelCount();
  const int K = kDenoiserCandidates;
  for (size_t i = 0; i < n; ++i) {
    if (!in.valid[i]) continue;
    float l[kDenoiserCandidates], w[kDenoiserCandidates];
    for (int k = 0; k < K; ++k) l[k] = kLogitBound * std::tanh(logits.data[i * K + k] / kLogitBound);
    float top = l[0], sum = 0.f;
    for (int k = 1; k < K; ++k) top = std::max(top, l[k]);
    for (int k = 0; k < K; ++k) sum += w[k] = std::exp(l[k] - top);
    for (int c = 0; c < 3; ++c) {
      float e = 0.f;
      for (int k = 0; k < K; ++k) e += w[k] * in.candidates[k].data[3 * i + c];
      result.data[3 * i + c] =
          in.scale * (e / sum) * std::max(footprint_albedo.data[3 * i + c], eps);
    }
  }
  return result;
}

void denoiseRgbLearned(Frame& frame, const RgbLayers& layers, const NeuralDenoiser& net) {
  ImageF reflected = frame.rgb;
  for (size_t i = 0; i < reflected.data.size(); ++i) reflected.data[i] -= layers.emission.data[i];
  frame.rgb = neuralDenoise(net, reflected, layers.variance, layers.albedo, frame.albedo,
                            frame.normal, frame.depth_z);
  for (size_t i = 0; i < frame.rgb.data.size(); ++i) frame.rgb.data[i] += layers.emission.data[i];
}

std::vector<std::string> denoiserDumpChannels() {
  return {"R",        "G",        "B",        "var.R",    "var.G",    "var.B",    "afp.R",
          "afp.G",    "afp.B",    "albedo.R", "albedo.G", "albedo.B", "normal.X", "normal.Y",
          "normal.Z", "Z",        "emission.R", "emission.G", "emission.B"};
}

ImageF denoiserDump(const Frame& frame, const RgbLayers& layers) {
  const ImageF& rgb = frame.rgb;
  checkSameSize(layers.emission, rgb, 3, "emission");
  checkSameSize(layers.variance, rgb, 3, "variance");
  checkSameSize(layers.albedo, rgb, 3, "footprint albedo");
  checkSameSize(frame.albedo, rgb, 3, "albedo");
  checkSameSize(frame.normal, rgb, 3, "normal");
  checkSameSize(frame.depth_z, rgb, 1, "depth");
  ImageF d(rgb.width, rgb.height, 19);
  for (size_t i = 0; i < rgb.pixelCount(); ++i) {
    float* o = &d.data[19 * i];
    for (int c = 0; c < 3; ++c) {
      o[c] = rgb.data[3 * i + c] - layers.emission.data[3 * i + c];
      o[3 + c] = layers.variance.data[3 * i + c];
      o[6 + c] = layers.albedo.data[3 * i + c];
      o[9 + c] = frame.albedo.data[3 * i + c];
      o[12 + c] = frame.normal.data[3 * i + c];
      o[16 + c] = layers.emission.data[3 * i + c];
    }
    o[15] = frame.depth_z.data[i];
  }
  return d;
}

DenoiserInput denoiserFeaturesFromDump(const ImageF& dump, float albedo_epsilon) {
  INET_CHECK(dump.channels == 19);
  auto slice = [&](int first, int count) { return channelRange(dump, first, count); };
  return denoiserFeatures(slice(0, 3), slice(3, 3), slice(6, 3), slice(9, 3), slice(12, 3),
                          slice(15, 1), albedo_epsilon);
}

void saveNeuralDenoiser(const NeuralDenoiser& net, const std::string& path) {
  nlohmann::json header{{"config",
                         {{"channels", net.config.channels},
                          {"leak", net.config.leak},
                          {"albedo_epsilon", net.config.albedo_epsilon}}},
                        {"tensors", nlohmann::json::array()}};
  std::vector<float> data;
  for (size_t i = 0; i < net.convs.size(); ++i) {
    const ConvLayer& c = net.convs[i];
    header["tensors"].push_back(
        {{"name", "conv" + std::to_string(i) + ".weight"}, {"shape", {c.out, c.in, c.k, c.k}}});
    header["tensors"].push_back({{"name", "conv" + std::to_string(i) + ".bias"}, {"shape", {c.out}}});
    data.insert(data.end(), c.weight.begin(), c.weight.end());
    data.insert(data.end(), c.bias.begin(), c.bias.end());
  }
  writeTextAtomic(path, encodeWeightsFile(std::string(kMagic, 8), kFormatVersion, header.dump(), data));
}

NeuralDenoiser loadNeuralDenoiser(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError(path, "", "cannot open the denoiser weights");
  const std::string bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  return parseNeuralDenoiser(bytes, path);
}

NeuralDenoiser parseNeuralDenoiser(const std::string& bytes, const std::string& path) {
  WeightsFileReader file(bytes, path, std::string(kMagic, 8), kFormatVersion,
                         "a denoiser weights file");
  NeuralDenoiser net;
  nlohmann::json header;
  try {
    header = nlohmann::json::parse(file.header());
    const auto& c = header.at("config");
    const auto& channels = c.at("channels");
    if (!channels.is_array() || channels.size() > 6)
      throw InputError(path, "config.channels", "needs 1 to 6 levels");
    net.config.channels.clear();
    for (const auto& v : channels) {
      // checked before converting: a float outside int's range would be undefined behaviour
      if (!v.is_number_integer() || v.get<int64_t>() < 1 || v.get<int64_t>() > kMaxChannels)
        throw InputError(path, "config.channels", "each level needs 1 to 256 channels");
      net.config.channels.push_back(v.get<int>());
    }
    for (const char* key : {"leak", "albedo_epsilon"})
      if (!c.at(key).is_number()) throw InputError(path, std::string("config.") + key, "not a number");
    const double leak = c.at("leak").get<double>(), eps = c.at("albedo_epsilon").get<double>();
    if (!(leak >= 0 && leak < 1)) throw InputError(path, "config.leak", "must be in [0, 1)");
    if (!(eps > 0 && eps <= 1)) throw InputError(path, "config.albedo_epsilon", "must be in (0, 1]");
    net.config.leak = static_cast<float>(leak);
    net.config.albedo_epsilon = static_cast<float>(eps);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path, "header", e.what());
  }
  net.config.validate(path);
  net.convs = NeuralDenoiser::shapes(net.config);
  const nlohmann::json& spec = header["tensors"];  // null when absent: fails the check below
  if (!spec.is_array() || spec.size() != 2 * net.convs.size())
    throw InputError(path, "tensors", "expected " + std::to_string(2 * net.convs.size()) +
                                          " tensors for the config");
  auto read = [&](std::vector<float>& v, size_t count, const std::string& name,
                  const std::vector<int>& shape, const nlohmann::json& s) {
    bool same = s.is_object() && s.contains("name") && s["name"].is_string() &&
                s["name"].get<std::string>() == name && s.contains("shape") &&
                s["shape"].is_array() && s["shape"].size() == shape.size();
    for (size_t d = 0; same && d < shape.size(); ++d)
      same = s["shape"][d].is_number_integer() && s["shape"][d].get<int64_t>() == shape[d];
    if (!same)
      throw InputError(path, "tensors", "expected " + name + " of shape " +
                                            nlohmann::json(shape).dump());
    v = file.readFloats(count, name);
    for (float f : v)
      if (!std::isfinite(f)) throw InputError(path, name, "holds a value that is not finite");
  };
  try {
    for (size_t i = 0; i < net.convs.size(); ++i) {
      ConvLayer& c = net.convs[i];
      const std::string base = "conv" + std::to_string(i);
      read(c.weight, static_cast<size_t>(c.out) * c.in * c.k * c.k, base + ".weight",
           {c.out, c.in, c.k, c.k}, spec[2 * i]);
      read(c.bias, static_cast<size_t>(c.out), base + ".bias", {c.out}, spec[2 * i + 1]);
    }
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path, "tensors", e.what());
  }
  file.finish();
  return net;
}

std::string defaultNeuralDenoiserPath() {
  namespace fs = std::filesystem;
  if (const char* env = std::getenv("INET_DENOISER"); env != nullptr && *env != '\0') return env;
  const fs::path source = INET_DENOISER_SOURCE_PATH;
  std::error_code ec;
  if (fs::exists(source, ec)) return source.string();
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path installed =
        exe.parent_path().parent_path() / "share/interiornet/denoise" / source.filename();
    if (fs::exists(installed, ec)) return installed.string();
  }
  return source.string();  // loading then names the expected file
}

const NeuralDenoiser& defaultNeuralDenoiser() {
  static const NeuralDenoiser net = loadNeuralDenoiser(defaultNeuralDenoiserPath());
  return net;
}

}  // namespace inet
