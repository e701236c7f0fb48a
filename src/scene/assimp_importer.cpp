#include "scene/assimp_importer.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/DefaultIOSystem.h>
#include <assimp/Importer.hpp>
#include <assimp/MemoryIOWrapper.h>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>

#include <unistd.h>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/text.h"
#include "core/image_io.h"
#include "core/rng.h"
#include "scene/label_map.h"
#include "scene/nyu40.h"
#include "scene/obj_prepass.h"
#include "scene/room_shell.h"

namespace fs = std::filesystem;

namespace inet {
namespace {

// Triangulate so every polygon becomes triangles; join identical vertices so shared corners are
// shared indices. No normal generation (a file without normals is shaded flat, as Cycles does)
// and nothing that pre-transforms, merges or reorders meshes across nodes (object identity must
// survive).
constexpr unsigned kImportFlags =
    aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_ValidateDataStructure;

std::string oneLine(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

Mat4 toEigen(const aiMatrix4x4& m) {
  Mat4 out;
  out << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3,
      m.d4;
  return out;
}

/// C = scale * R_up: file coordinates -> world (metres, Z up).
Mat4 fileToWorld(double scale, char up) {
  Mat4 c = Mat4::Identity();
  if (up == 'y') {  // x -> x, y -> z, z -> -y
    c.block<3, 3>(0, 0) << 1, 0, 0, 0, 0, -1, 0, 1, 0;
  }
  c.block<3, 3>(0, 0) *= scale;
  return c;
}

void checkAxes(double scale, char up, const std::string& file, const std::string& field) {
  if (!(std::isfinite(scale) && scale > 0))
    throw InputError(file, field, fmt::format("scale must be a finite number > 0, got {}", scale));
  if (up != 'y' && up != 'z')
    throw InputError(file, field, fmt::format("up axis must be 'y' or 'z', got '{}'", up));
}

/// Assimp's file system, but for one file whose text is given (an OBJ file rewritten by
/// prepassObj): the MTL files and textures it names are still read from its folder.
class PatchedFileSystem : public Assimp::DefaultIOSystem {
 public:
  PatchedFileSystem(const std::string& path, std::string text)
      : path_(fs::absolute(path).lexically_normal()), text_(std::move(text)) {}
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    std::error_code ec;
    if (fs::absolute(file, ec).lexically_normal() == path_)
      return new Assimp::MemoryIOStream(reinterpret_cast<const uint8_t*>(text_.data()),
                                        text_.size());
    return DefaultIOSystem::Open(file, mode);
  }

 private:
  fs::path path_;
  std::string text_;
};

/// Reads `path` with Assimp (an OBJ file through prepassObj first, whose findings go to
/// `prepass` when given). The importer owns the returned scene.
std::unique_ptr<Assimp::Importer> readFile(const std::string& path, const std::string& where_file,
                                           const std::string& where_field,
                                           ObjPrepass* prepass = nullptr) {
  const bool self = (where_file == path);  // errors about the file itself need not repeat it
  const std::string what = self ? std::string() : fmt::format("'{}': ", path);
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError(where_file, where_field, what + "file not found");
  if (fs::is_directory(path, ec))
    throw InputError(where_file, where_field, what + "is a folder, expected a mesh file");
  auto importer = std::make_unique<Assimp::Importer>();
  if (lowerExtension(path) == ".obj") {
    ObjPrepass pre;
    try {
      pre = prepassObj(path);
    } catch (const InputError& e) {
      if (self) throw;
      throw InputError(where_file, where_field, what + e.field() + ": " + e.problem());
    }
    if (!pre.text.empty()) importer->SetIOHandler(new PatchedFileSystem(path, pre.text));
    if (prepass) *prepass = std::move(pre);
  }
  const aiScene* scene = importer->ReadFile(path, kImportFlags);
  if (!scene || !scene->mRootNode)
    throw InputError(where_file, where_field,
                     what + "cannot import: " + oneLine(importer->GetErrorString()));
  if (scene->mNumMeshes == 0)
    throw InputError(where_file, where_field, what + "the file contains no meshes");
  return importer;
}

/// Calls visit(node, T_file_node) for every node, parents first, children in file order.
void walkNodes(const aiNode* node, const Mat4& T_parent,
               const std::function<void(const aiNode*, const Mat4&)>& visit) {
  Mat4 T = T_parent * toEigen(node->mTransformation);
  visit(node, T);
  for (unsigned c = 0; c < node->mNumChildren; ++c) walkNodes(node->mChildren[c], T, visit);
}

/// Vertex normals further than this from their triangle's face normal mark a hard edge that the
/// file smoothed over (see MeshBuilder::flattenHardEdges).
constexpr float kMaxNormalDeviationDeg = 35.f;

/// Collects triangles of one or more aiMeshes into a Mesh. Normals are kept only when every part
/// has valid ones (otherwise the merged mesh is shaded flat); texture coordinates when any part
/// has them (parts without read (0, 0)).
struct MeshBuilder {
  Mesh mesh;
  bool all_normals = true;
  bool any_uvs = false;

  /// Appends the triangles of `in` with positions mapped by `M` (winding flipped when M
  /// mirrors), normals by its inverse transpose. Only vertices used by a triangle are copied.
  /// Returns the number of non-triangle faces dropped.
  size_t append(const aiMesh* in, const Mat4& M) {
    const bool flip = M.block<3, 3>(0, 0).determinant() < 0;
    const Mat3 N = M.block<3, 3>(0, 0).inverse().transpose();
    const bool has_normals = in->mNormals != nullptr, has_uvs = in->HasTextureCoords(0);
    all_normals = all_normals && has_normals;
    any_uvs = any_uvs || has_uvs;
    std::vector<int64_t> remap(in->mNumVertices, -1);
    size_t dropped = 0;
    for (unsigned f = 0; f < in->mNumFaces; ++f) {
      const aiFace& face = in->mFaces[f];
      if (face.mNumIndices != 3) {
        ++dropped;
        continue;
      }
      Tri tri;
      for (int k = 0; k < 3; ++k) {
        unsigned v = face.mIndices[k];
        if (remap[v] < 0) {
          remap[v] = static_cast<int64_t>(mesh.positions.size());
          const aiVector3D& p = in->mVertices[v];
          Vec3 w = (M * Eigen::Vector4d(p.x, p.y, p.z, 1.0)).head<3>();
          mesh.positions.push_back(w.cast<float>());
          Vec3 n = Vec3::UnitZ();
          if (has_normals) {
            const aiVector3D& a = in->mNormals[v];
            n = N * Vec3(a.x, a.y, a.z);
            if (!(n.allFinite() && n.norm() > 1e-12)) all_normals = false;  // broken: go flat
          }
          mesh.normals.push_back(n.allFinite() && n.norm() > 1e-12
                                     ? Vec3f(n.normalized().cast<float>())
                                     : Vec3f::UnitZ());
          const aiVector3D uv = has_uvs ? in->mTextureCoords[0][v] : aiVector3D(0, 0, 0);
          mesh.uvs.emplace_back(uv.x, uv.y);
        }
        tri[k] = static_cast<uint32_t>(remap[v]);
      }
      if (flip) std::swap(tri[1], tri[2]);
      mesh.triangles.push_back(tri);
    }
    return dropped;
  }

  /// The mesh; `flattened` counts triangles whose vertex normals were replaced (see below).
  Mesh finish(size_t* flattened = nullptr) {
    if (!all_normals) mesh.normals.clear();
    if (!any_uvs || !std::all_of(mesh.uvs.begin(), mesh.uvs.end(),
                                 [](const Vec2f& uv) { return uv.allFinite(); }))
      mesh.uvs.clear();
    if (!mesh.normals.empty()) flattenHardEdges(flattened);
    return std::move(mesh);
  }

  /// Exporters often smooth across hard edges (SceneNet's walls and floors are boxes with one
  /// smoothing group, so a corner's normal is the mean of three faces, 55 degrees off each): a
  /// flat wall then shades with a gradient. A triangle with a vertex normal more than
  /// kMaxNormalDeviationDeg off its face normal gets its own three vertices with the face
  /// normal (flat). Genuinely smooth meshes stay smooth: a 6-sided cylinder's normals deviate by
  /// 30 degrees.
  void flattenHardEdges(size_t* flattened) {
    static const float kCos = std::cos(kMaxNormalDeviationDeg * static_cast<float>(M_PI) / 180.f);
    const bool uvs = !mesh.uvs.empty();
    for (Tri& t : mesh.triangles) {
      const Vec3f e1 = mesh.positions[t[1]] - mesh.positions[t[0]];
      const Vec3f e2 = mesh.positions[t[2]] - mesh.positions[t[0]];
      const Vec3f c = e1.cross(e2);
      if (!(c.norm() > 0.f)) continue;  // degenerate: never hit
      const Vec3f face = c.normalized();
      bool hard = false;
      for (int k = 0; k < 3; ++k) hard = hard || mesh.normals[t[k]].dot(face) < kCos;
      if (!hard) continue;
      for (int k = 0; k < 3; ++k) {
        mesh.positions.push_back(mesh.positions[t[k]]);
        mesh.normals.push_back(face);
        if (uvs) mesh.uvs.push_back(mesh.uvs[t[k]]);
        t[k] = static_cast<uint32_t>(mesh.positions.size() - 1);
      }
      if (flattened) ++*flattened;
    }
  }
};

size_t countTriangles(const aiMesh* m) {
  size_t n = 0;
  for (unsigned f = 0; f < m->mNumFaces; ++f) n += (m->mFaces[f].mNumIndices == 3);
  return n;
}


std::string uniqueId(std::string base, std::set<std::string>& used) {
  if (base.empty()) base = "unnamed";
  std::string id = base;
  for (int k = 2; used.count(id); ++k) id = fmt::format("{}_{}", base, k);
  used.insert(id);
  return id;
}

Vec3f readColor(const aiMaterial* m, const char* key, unsigned type, unsigned index,
                const Vec3f& fallback) {
  aiColor3D c;
  if (m->Get(key, type, index, c) != AI_SUCCESS) return fallback;
  return Vec3f(c.r, c.g, c.b);
}

/// The image a material's texture slot names, resolved against the model's folder, or an empty
/// ref. A folder (SceneNet's `map_Kd ../texture_library/wall` picks one image of a folder at
/// random) resolves to one of its images, chosen by a hash of the material name so that the
/// choice is the same on every run. Embedded textures ("*0") and missing files are counted in
/// the report and ignored.
/// Writes an image embedded in the scene file (a glTF data URI, a .glb buffer view) into the
/// cache and returns its path, or "" when it cannot be read.
fs::path extractEmbedded(const aiTexture* tex) {
  if (!tex || !tex->pcData || tex->mWidth == 0) return {};
  std::string bytes, ext;
  if (tex->mHeight == 0) {  // compressed: mWidth bytes of a PNG/JPEG file
    bytes.assign(reinterpret_cast<const char*>(tex->pcData), tex->mWidth);
    ext = tex->achFormatHint;
    if (ext == "jpeg") ext = "jpg";
    if (ext != "png" && ext != "jpg") return {};
  } else {  // raw texels, BGRA: written as an 8-bit RGBA PNG
    ImageU8 img(static_cast<int>(tex->mWidth), static_cast<int>(tex->mHeight), 4);
    for (unsigned y = 0; y < tex->mHeight; ++y)
      for (unsigned x = 0; x < tex->mWidth; ++x) {
        const aiTexel& t = tex->pcData[y * tex->mWidth + x];
        img.at(x, y, 0) = t.r, img.at(x, y, 1) = t.g, img.at(x, y, 2) = t.b, img.at(x, y, 3) = t.a;
      }
    bytes.assign(reinterpret_cast<const char*>(img.data.data()), img.data.size());
    const fs::path out = embeddedTextureCache() / fmt::format("{:016x}.png", stableHash(bytes));
    if (!fs::exists(out)) writePng(out, img);
    return out;
  }
  const fs::path out = embeddedTextureCache() / fmt::format("{:016x}.{}", stableHash(bytes), ext);
  std::error_code ec;
  if (!fs::exists(out, ec))
    writeFileAtomic(out, [&](const fs::path& tmp) {
      std::ofstream(tmp, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    });
  return out;
}

TextureRef textureOf(const aiScene* ai, const aiMaterial* in, aiTextureType type,
                     const std::string& material, const fs::path& model_dir,
                     ImportReport& report) {
  aiString file;
  if (in->GetTextureCount(type) == 0 || in->GetTexture(type, 0, &file) != AI_SUCCESS) return {};
  std::string written = file.C_Str();
  if (written.empty()) return {};
  if (const aiTexture* embedded = ai->GetEmbeddedTexture(file.C_Str())) {
    const fs::path path = extractEmbedded(embedded);
    if (path.empty()) {
      ++report.skipped_textures;
      if (report.missing_textures.size() < 5) report.missing_textures.push_back(written);
      return {};
    }
    ++report.embedded_textures;
    TextureRef ref;
    ref.path = ref.file = path.string();
    return ref;
  }
  if (written[0] == '*') {
    ++report.skipped_textures;
    return {};
  }
  std::replace(written.begin(), written.end(), '\\', '/');
  fs::path path = fs::path(written).is_absolute() ? fs::path(written) : model_dir / written;
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    std::vector<fs::path> images;
    for (const auto& e : fs::directory_iterator(path, ec)) {
      const std::string ext = lowerExtension(e.path().string());
      if (e.is_regular_file(ec) && (ext == ".jpg" || ext == ".jpeg" || ext == ".png"))
        images.push_back(e.path());
    }
    std::sort(images.begin(), images.end());
    if (images.empty()) {
      ++report.skipped_textures;
      if (report.missing_textures.size() < 5) report.missing_textures.push_back(written);
      return {};
    }
    const uint64_t h = stableHash(material);  // the same image on every run
    path = images[h % images.size()];
  }
  if (!fs::is_regular_file(path, ec)) {
    // Files written on the modeller's machine name textures where they were there
    // ("C:/Documents and Settings/.../wood.jpg", "/Users/.../TEXTURES/Living room rug.jpg")
    // and ship them beside the model. Look there by file name, and by the last word of the
    // name, which is what Sweet Home 3D's OBJ reader takes (its catalogs rely on it).
    std::vector<fs::path> candidates = {model_dir / fs::path(written).filename()};
    const size_t blank = written.find_last_of(" \t");
    if (blank != std::string::npos)
      candidates.push_back(model_dir / fs::path(written.substr(blank + 1)).filename());
    const auto found = std::find_if(candidates.begin(), candidates.end(), [&](const fs::path& c) {
      return !c.filename().empty() && fs::is_regular_file(c, ec);
    });
    if (found == candidates.end()) {
      ++report.skipped_textures;
      if (report.missing_textures.size() < 5) report.missing_textures.push_back(written);
      return {};
    }
    path = *found;
    ++report.relocated_textures;
  }
  TextureRef ref;
  ref.path = ref.file = path.lexically_normal().string();
  return ref;
}

/// Lambertian material from an Assimp material: diffuse colour (clamped to [0, 1]) and emissive
/// colour (negative parts clamped to 0), both taken as linear RGB as OBJ Kd/Ke and glTF are; the
/// diffuse and normal textures. With a diffuse texture an OBJ's Kd is ignored (the texture is the
/// colour, as in Blender's importer); other formats' diffuse colour is glTF's base-colour factor,
/// which multiplies the texture.
Material convertMaterial(const aiScene* ai, const aiMaterial* in, const fs::path& model_dir, bool is_obj,
                         std::set<std::string>& used_ids, ImportReport& report) {
  Material mat;
  aiString name;
  in->Get(AI_MATKEY_NAME, name);
  mat.id = uniqueId(name.C_Str(), used_ids);
  Vec3f albedo = readColor(in, AI_MATKEY_COLOR_DIFFUSE, mat.albedo);
  Vec3f emission = readColor(in, AI_MATKEY_COLOR_EMISSIVE, mat.emission);
  const Vec3f ambient = readColor(in, AI_MATKEY_COLOR_AMBIENT, Vec3f::Zero());
  if (!albedo.allFinite()) albedo = Material().albedo;
  if (!emission.allFinite()) emission.setZero();
  // Older OBJ files (Cornell boxes among them) give a light only as Ka, the ambient colour:
  // with no Ke and a Ka above 1, which no reflectance can be, the file means emitted light.
  // Ka <= 1 stays ambient (Blender writes Ka 1 1 1 for every material).
  if (!(emission.maxCoeff() > 0.f) && ambient.allFinite() && ambient.maxCoeff() > 1.f) {
    emission = ambient;
    report.ka_emission_materials.push_back(name.C_Str());
  }
  if (albedo.minCoeff() < 0.f || albedo.maxCoeff() > 1.f) ++report.clamped_materials;
  mat.albedo = albedo.cwiseMax(0.f).cwiseMin(1.f);
  mat.emission = emission.cwiseMax(0.f);
  mat.albedo_texture = textureOf(ai, in, aiTextureType_DIFFUSE, name.C_Str(), model_dir, report);
  if (mat.albedo_texture.empty())  // glTF 2's base colour (Assimp 5.2 keeps it apart)
    mat.albedo_texture = textureOf(ai, in, aiTextureType_BASE_COLOR, name.C_Str(), model_dir, report);
  mat.normal_texture = textureOf(ai, in, aiTextureType_NORMALS, name.C_Str(), model_dir, report);
  if (!mat.albedo_texture.empty() && is_obj) mat.albedo = Vec3f::Ones();
  if (in->GetTextureCount(aiTextureType_HEIGHT) > 0) ++report.ignored_bump_maps;
  return mat;
}

/// Builds the object-space mesh of aiMesh `index`, or returns -1 when it has no triangles.
int addSharedMesh(const aiScene* ai, unsigned index, const Mat4& C, Scene& scene,
                  std::set<std::string>& used_ids, ImportReport& report) {
  const aiMesh* in = ai->mMeshes[index];
  MeshBuilder builder;
  report.dropped_faces += builder.append(in, C);
  Mesh mesh = builder.finish(&report.flattened_triangles);
  if (mesh.triangles.empty()) return -1;
  mesh.id = uniqueId(in->mName.C_Str(), used_ids);
  mesh.source.kind = MeshSource::Kind::Inline;
  scene.meshes.push_back(std::move(mesh));
  return static_cast<int>(scene.meshes.size()) - 1;
}

/// Node transforms are conjugated into world axes; a transform that is not a proper rigid or
/// similarity map (mirror, degenerate, projective) cannot share the mesh, so that instance is
/// baked into its own mesh with an identity transform.
bool canShare(const Mat4& T_world) {
  return T_world.allFinite() && T_world.row(3) == Eigen::RowVector4d(0, 0, 0, 1) &&
         T_world.block<3, 3>(0, 0).determinant() > 1e-12;
}

int resolveLabel(const LabelMap& labels, const std::string& name, int default_id,
                 ImportReport& report, std::set<std::string>& unmatched_seen) {
  if (auto id = labels.lookup(name)) return *id;
  ++report.unmatched_objects;
  if (unmatched_seen.insert(name).second) report.unmatched_names.push_back(name);
  return default_id;
}

/// T_world = C T_file C^-1 for C = scale * R_up, computed exactly: R_up is a signed permutation,
/// so the rotation part is only permuted and the translation only scaled.
Mat4 fileTransformToWorld(const Mat4& T_file, double scale, char up) {
  const Mat3 R = fileToWorld(1.0, up).block<3, 3>(0, 0);
  Mat4 T = T_file;
  T.block<3, 3>(0, 0) = R * T_file.block<3, 3>(0, 0) * R.transpose();
  T.block<3, 1>(0, 3) = scale * (R * T_file.block<3, 1>(0, 3));
  return T;
}

/// A value from a node's metadata (glTF node extras, as Assimp reads them; our glTF export
/// writes nyu40, instance, kind, part, mass_kg, friction, movable there).
std::optional<double> metaNumber(const aiNode* node, const char* key) {
  const aiMetadata* md = node->mMetaData;
  if (!md) return std::nullopt;
  for (unsigned i = 0; i < md->mNumProperties; ++i) {
    if (std::strcmp(md->mKeys[i].C_Str(), key) != 0) continue;
    const void* v = md->mValues[i].mData;
    switch (md->mValues[i].mType) {
      case AI_INT32: return *static_cast<const int32_t*>(v);
      case AI_UINT64: return static_cast<double>(*static_cast<const uint64_t*>(v));
      case AI_FLOAT: return *static_cast<const float*>(v);
      case AI_DOUBLE: return *static_cast<const double*>(v);
      case AI_BOOL: return *static_cast<const bool*>(v) ? 1.0 : 0.0;
      default: return std::nullopt;
    }
  }
  return std::nullopt;
}

std::string metaString(const aiNode* node, const char* key) {
  aiString s;
  if (node->mMetaData && node->mMetaData->Get(key, s)) return s.C_Str();
  return {};
}

/// The node's integer metadata `key` when it is a whole number in [lo, hi].
std::optional<int> metaInt(const aiNode* node, const char* key, int lo, int hi) {
  auto v = metaNumber(node, key);
  if (!v || *v != std::floor(*v) || *v < lo || *v > hi) return std::nullopt;
  return static_cast<int>(*v);
}

/// Turns (node, aiMesh) pairs into Objects, sharing meshes and materials as it goes.
struct SceneBuilder {
  SceneBuilder(const aiScene* ai, const std::string& path, const ImportOptions& opt,
               const LabelMap& labels, int default_id)
      : ai(ai),
        path(path),
        opt(opt),
        labels(labels),
        default_id(default_id),
        C(fileToWorld(opt.scale, opt.up)),
        shared_mesh(ai->mNumMeshes, -2),
        material_of(ai->mNumMaterials, -1),
        model_dir(fs::path(path).parent_path()),
        is_obj(lowerExtension(path) == ".obj") {
    // instance ids a file states (our glTF export) are kept; named objects get the others
    walkNodes(ai->mRootNode, Mat4::Identity(), [&](const aiNode* node, const Mat4&) {
      if (auto id = metaInt(node, "instance", 1, 65535)) stated_instances.insert(*id);
    });
  }

  void addNode(const aiNode* node, const Mat4& T_file) {
    const Mat4 T_world = fileTransformToWorld(T_file, opt.scale, opt.up);
    for (unsigned k = 0; k < node->mNumMeshes; ++k) {
      const unsigned mi = node->mMeshes[k];
      const aiMesh* in = ai->mMeshes[mi];
      if (countTriangles(in) == 0) {
        report.dropped_faces += in->mNumFaces;
        continue;
      }
      Object obj;
      obj.name = node->mName.length ? node->mName.C_Str() : in->mName.C_Str();
      if (obj.name.empty()) obj.name = "object";
      if (canShare(T_world)) {
        if (shared_mesh[mi] == -2)
          shared_mesh[mi] = addSharedMesh(ai, mi, C, scene, mesh_ids, report);
        obj.mesh = shared_mesh[mi];
        obj.T_world_object = T_world;
      } else {
        MeshBuilder builder;
        report.dropped_faces += builder.append(in, C * T_file);
        Mesh baked = builder.finish(&report.flattened_triangles);
        baked.id = uniqueId(obj.name, mesh_ids);
        scene.meshes.push_back(std::move(baked));
        obj.mesh = static_cast<int>(scene.meshes.size()) - 1;
      }
      obj.material = materialIndex(in->mMaterialIndex);
      const auto stated_class = metaInt(node, "nyu40", 0, 40);
      obj.nyu40 = stated_class ? *stated_class
                               : resolveLabel(labels, obj.name, default_id, report, unmatched_seen);
      if (auto id = metaInt(node, "instance", 1, 65535)) {
        obj.instance = *id;
      } else {
        auto [it, fresh] = instance_of.emplace(obj.name, 0);
        if (fresh) {
          while (stated_instances.count(++next_instance)) {
          }
          it->second = next_instance;
        }
        if (it->second > 65535)
          throw InputError(path, obj.name, "more than 65535 distinct object names (instance ids)");
        obj.instance = it->second;
      }
      obj.kind = metaString(node, "kind");
      obj.part = metaString(node, "part");
      const auto mass = metaNumber(node, "mass_kg"), friction = metaNumber(node, "friction");
      if (mass && *mass > 0 && friction && *friction >= 0) {
        obj.physics = PhysicsProps{static_cast<float>(*mass), static_cast<float>(*friction),
                                   metaNumber(node, "movable").value_or(0.0) != 0.0};
      }
      scene.objects.push_back(std::move(obj));
    }
  }

  /// The file's lights, placed by their nodes (`node_T`: file transform of each named node).
  /// Only glTF states units (KHR_lights_punctual: candela and lux, which Assimp keeps as colour
  /// x intensity); they are turned into ours at 683 lm/W, as our glTF export writes them.
  void addLights(const std::map<std::string, Mat4>& node_T, bool gltf) {
    for (unsigned i = 0; i < ai->mNumLights; ++i) {
      const aiLight* in = ai->mLights[i];
      auto it = node_T.find(in->mName.C_Str());
      const bool known = in->mType == aiLightSource_POINT || in->mType == aiLightSource_SPOT ||
                         in->mType == aiLightSource_DIRECTIONAL;
      if (!gltf || !known || it == node_T.end()) {
        ++report.skipped_lights;
        continue;
      }
      const Vec3f rgb =
          Vec3f(in->mColorDiffuse.r, in->mColorDiffuse.g, in->mColorDiffuse.b) / 683.f;
      if (!(rgb.maxCoeff() > 0.f) || !rgb.allFinite()) {
        ++report.skipped_lights;
        continue;
      }
      // the light's position and direction are in its node's frame: world = C T_file x
      const Mat4 T = C * it->second;
      Light l;
      l.name = in->mName.C_Str();
      l.intensity = rgb.maxCoeff();
      l.color = rgb / l.intensity;
      l.position = (T * Eigen::Vector4d(in->mPosition.x, in->mPosition.y, in->mPosition.z, 1.0))
                       .head<3>();
      const Vec3 d = T.block<3, 3>(0, 0) * Vec3(in->mDirection.x, in->mDirection.y,
                                                in->mDirection.z);
      l.direction = d.norm() > 0 ? Vec3(d.normalized()) : Vec3(-Vec3::UnitZ());
      if (in->mType == aiLightSource_POINT) {
        l.type = LightType::Point;
      } else if (in->mType == aiLightSource_SPOT) {
        l.type = LightType::Spot;
        // Assimp keeps glTF's cone angles, measured from the axis
        l.cone_deg = static_cast<float>(in->mAngleOuterCone * 180.0 / M_PI);
        l.falloff_deg = std::clamp(
            static_cast<float>((in->mAngleOuterCone - in->mAngleInnerCone) * 180.0 / M_PI), 0.f,
            l.cone_deg);
      } else {
        l.type = LightType::Sun;
      }
      scene.lights.push_back(l);
      ++report.lights;
    }
  }

  int materialIndex(unsigned ai_index) {
    int& mat = material_of[ai_index];
    if (mat < 0) {
      const aiMaterial* in = ai->mMaterials[ai_index];
      scene.materials.push_back(convertMaterial(ai, in, model_dir, is_obj, material_ids, report));
      if (opt.phong_materials) {
        float shininess = 0.f, opacity = 1.f;
        in->Get(AI_MATKEY_SHININESS, shininess);
        in->Get(AI_MATKEY_OPACITY, opacity);
        phongToMaterial(readColor(in, AI_MATKEY_COLOR_SPECULAR, Vec3f::Zero()), shininess,
                        opacity, scene.materials.back());
      }
      mat = static_cast<int>(scene.materials.size()) - 1;
    }
    return mat;
  }

  const aiScene* ai;
  const std::string& path;
  const ImportOptions& opt;
  const LabelMap& labels;
  const int default_id;
  const Mat4 C;
  std::vector<int> shared_mesh;  ///< per aiMesh: -2 = not built yet, -1 = no triangles
  std::vector<int> material_of;  ///< per aiMaterial: index in scene.materials or -1
  const fs::path model_dir;      ///< textures are named relative to the model file
  const bool is_obj;
  std::set<std::string> mesh_ids, material_ids, unmatched_seen;
  std::map<std::string, int> instance_of;
  std::set<int> stated_instances;  ///< instance ids in the file's node metadata
  int next_instance = 0;
  Scene scene;
  ImportReport report;
};

}  // namespace

std::string ImportReport::summary(const std::string& default_category) const {
  std::vector<std::string> parts;
  if (unmatched_objects > 0) {
    parts.push_back(fmt::format(
        "{} object(s) ({} distinct name(s)) matched no label and were labelled '{}': {}",
        unmatched_objects, unmatched_names.size(), default_category,
        listNames(unmatched_names, 10)));
  }
  if (dropped_faces > 0)
    parts.push_back(
        fmt::format("{} non-triangle face(s) (lines or points) were skipped", dropped_faces));
  if (flattened_triangles > 0)
    parts.push_back(fmt::format(
        "{} triangle(s) had vertex normals smoothed across a hard edge (more than {} degrees "
        "off the face) and are shaded flat",
        flattened_triangles, kMaxNormalDeviationDeg));
  if (skipped_textures > 0)
    parts.push_back(fmt::format(
        "{} texture(s) were missing, an empty folder or an unreadable embedded image and were "
        "skipped ({})",
        skipped_textures, listNames(missing_textures)));
  if (relocated_textures > 0)
    parts.push_back(fmt::format("{} texture(s) named with a path of another machine were found "
                                "beside the model by file name",
                                relocated_textures));
  if (ignored_bump_maps > 0)
    parts.push_back(fmt::format(
        "{} material(s) have a bump (height) map, which is not supported and was ignored",
        ignored_bump_maps));
  if (!missing_mtllibs.empty())
    parts.push_back(fmt::format("material library {} not found next to the file",
                                listNames(missing_mtllibs)));
  if (!grey_materials.empty())
    parts.push_back(fmt::format("{} material(s) defined in no material library get a default "
                                "grey ({})",
                                grey_materials.size(), listNames(grey_materials)));
  if (obj_missing_normals > 0)
    parts.push_back(fmt::format("{} face corner(s) name a normal the file does not have; they "
                                "are shaded without it",
                                obj_missing_normals));
  if (obj_w_values > 0)
    parts.push_back(fmt::format("{} vertex line(s) have a 4th (w) value, ignored as for "
                                "polygons it means nothing (Assimp would divide by it)",
                                obj_w_values));
  if (obj_leading_dots > 0)
    parts.push_back(fmt::format("{} number(s) written with a leading dot (.5) were read as 0.5",
                                obj_leading_dots));
  if (obj_late_groups > 0)
    parts.push_back(fmt::format(
        "{} group name(s) come after their faces (`usemtl NAME`, faces, then `g NAME`, as in "
        "McGuire's archive): those faces were given the group NAME",
        obj_late_groups));
  if (extent_m > 200.0)
    parts.push_back(fmt::format(
        "the scene is {:.0f} m across: if its unit is not the metre, give --scale (0.01 for "
        "centimetres, 0.001 for millimetres)",
        extent_m));
  if (skipped_lights > 0)
    parts.push_back(fmt::format(
        "{} light(s) in the file were left out: only glTF's KHR_lights_punctual states units "
        "(use --lights or --auto-lights)",
        skipped_lights));
  if (split_shells > 0)
    parts.push_back(fmt::format(
        "{} object(s) labelled wall held the room's floor or ceiling too: split into floor and "
        "ceiling objects of their own (docs/import.md)",
        split_shells));
  if (!ka_emission_materials.empty()) {
    const std::string names = listNames(ka_emission_materials, 10);
    parts.push_back(fmt::format(
        "{} material(s) have no emission (Ke) but an ambient colour (Ka) above 1, which no "
        "reflectance can be: Ka is taken as their emitted radiance ({}); give them Ke to say "
        "otherwise",
        ka_emission_materials.size(), names));
  }
  if (clamped_materials > 0)
    parts.push_back(fmt::format(
        "{} material(s) had a diffuse colour outside [0, 1] and were clamped", clamped_materials));
  std::string out;
  for (size_t i = 0; i < parts.size(); ++i) out += (i ? "; " : "") + parts[i];
  return out;
}

void phongToMaterial(const Vec3f& specular, float shininess, float opacity, Material& mat) {
  if (std::isfinite(opacity) && opacity < 0.99f) {
    const float d = std::max(0.f, opacity);
    mat.type = MaterialType::ThinDielectric;
    mat.transmittance = (Vec3f::Constant(1.f - d) + d * mat.albedo).cwiseMin(1.f);
    mat.ior = 1.5f;
  } else if (specular.allFinite() && specular.maxCoeff() > 0.04f && std::isfinite(shininess) &&
             shininess > 1.f) {
    mat.type = MaterialType::Plastic;
    mat.roughness = std::clamp(std::pow(2.f / (shininess + 2.f), 0.25f), 0.05f, 1.f);
    mat.ior = 1.5f;
  }
}

fs::path embeddedTextureCache() {
  return userCacheDir("embedded");
}

char detectUpAxis(const Scene& scene, const std::string& path, std::string* why) {
  const std::string ext = lowerExtension(path);
  if (ext == ".gltf" || ext == ".glb") {
    if (why) *why = "Y-up: glTF files are Y-up by their specification";
    return 'y';
  }
  const int floor = *nyu40FromName("floor"), ceiling = *nyu40FromName("ceiling");
  Vec3 labelled = Vec3::Zero(), all = Vec3::Zero();  // area facing along x, y, z
  for (const Object& o : scene.objects) {
    const Mesh& m = scene.meshes[o.mesh];
    const Mat3 R = o.T_world_object.block<3, 3>(0, 0);
    for (const Tri& t : m.triangles) {
      const Vec3 a = R * m.positions[t[0]].cast<double>(), b = R * m.positions[t[1]].cast<double>(),
                 c = R * m.positions[t[2]].cast<double>();
      const Vec3 n = (b - a).cross(c - a);  // |n| = twice the area
      const double len = n.norm();
      if (!(len > 0)) continue;
      for (int k = 0; k < 3; ++k) {
        if (std::abs(n[k]) < 0.9 * len) continue;
        all[k] += 0.5 * len;
        if (o.nyu40 == floor || o.nyu40 == ceiling) labelled[k] += 0.5 * len;
      }
    }
  }
  const bool by_labels = labelled.y() + labelled.z() > 0;
  const Vec3& area = by_labels ? labelled : all;
  const char up = area.y() > area.z() ? 'y' : 'z';
  if (why)
    *why = fmt::format("{} {:.1f} m^2 of {} face along y and {:.1f} m^2 along z", up == 'y' ? "Y-up:" : "Z-up:",
                       area.y(), by_labels ? "its floor and ceiling objects" : "its triangles",
                       area.z());
  return up;
}

Scene importMeshScene(const std::string& path, const ImportOptions& opt, ImportReport* report_out) {
  if (opt.up == 'a') {
    ImportOptions raw = opt;
    raw.up = 'z';
    raw.split_shells = false;  // the floors and ceilings must not be guessed in a wrong frame
    ImportReport report;
    Scene s = importMeshScene(path, raw, &report);
    std::string why;
    raw.up = detectUpAxis(s, path, &why);
    raw.split_shells = opt.split_shells;
    if (raw.up == 'y') {
      s = importMeshScene(path, raw, &report);
    } else if (opt.split_shells) {
      report.split_shells = splitRoomShells(s);
      report.objects = s.objects.size();
    }
    report.up_reason = why;
    if (report_out) *report_out = std::move(report);
    return s;
  }
  checkAxes(opt.scale, opt.up, path, "import options");
  auto default_id = nyu40FromName(opt.default_category);
  if (!default_id)
    throw InputError(
        path, "default_category",
        fmt::format("unknown NYU40 class '{}' (valid: {})", opt.default_category, nyu40NameList()));
  const LabelMap labels = opt.label_map.empty() ? LabelMap() : LabelMap::load(opt.label_map);
  ObjPrepass prepass;
  auto importer = readFile(path, path, "", &prepass);
  SceneBuilder builder(importer->GetScene(), path, opt, labels, *default_id);
  builder.report.obj_w_values = prepass.w_values;
  builder.report.obj_missing_normals = prepass.missing_normals;
  builder.report.obj_leading_dots = prepass.leading_dots;
  builder.report.obj_late_groups = prepass.late_groups;
  builder.report.missing_mtllibs = prepass.missing_mtllibs;
  builder.report.grey_materials = prepass.grey_materials;
  std::map<std::string, Mat4> node_T;  // for the lights, which Assimp names after their node
  walkNodes(importer->GetScene()->mRootNode, Mat4::Identity(),
            [&](const aiNode* node, const Mat4& T_file) {
              builder.addNode(node, T_file);
              node_T.emplace(node->mName.C_Str(), T_file);
            });
  const std::string ext = lowerExtension(path);
  builder.addLights(node_T, ext == ".gltf" || ext == ".glb");
  Scene& scene = builder.scene;
  scene.name = fs::path(path).stem().string();
  if (scene.objects.empty())
    throw NoSurfaceError(path, "", "the file contains no triangles (only lines or points?)");
  if (opt.split_shells) builder.report.split_shells = splitRoomShells(scene);
  const auto [lo, hi] = scene.bounds();
  builder.report.extent_m = (hi - lo).maxCoeff();
  builder.report.objects = scene.objects.size();
  scene.validate(path);
  builder.report.up = opt.up;
  if (report_out) *report_out = std::move(builder.report);
  return std::move(scene);
}

Mesh loadMeshFile(const std::string& path, double scale, char up, const std::string& mesh_name,
                  const std::string& where_file, const std::string& where_field) {
  checkAxes(scale, up, where_file, where_field);
  auto importer = readFile(path, where_file, where_field);
  const aiScene* ai = importer->GetScene();
  const Mat4 C = fileToWorld(scale, up);
  MeshBuilder builder;
  std::vector<std::string> names;  // for the "no such part" message
  bool matched = false;
  walkNodes(ai->mRootNode, Mat4::Identity(), [&](const aiNode* node, const Mat4& T_file) {
    for (unsigned k = 0; k < node->mNumMeshes; ++k) {
      const aiMesh* in = ai->mMeshes[node->mMeshes[k]];
      const std::string node_name = node->mName.C_Str(), part_name = in->mName.C_Str();
      if (!mesh_name.empty() && node_name != mesh_name && part_name != mesh_name) {
        if (names.empty() || names.back() != node_name) names.push_back(node_name);
        continue;
      }
      matched = true;
      builder.append(in, C * T_file);
    }
  });
  const std::string what = where_file == path ? std::string() : fmt::format("'{}': ", path);
  if (!matched) {
    std::string list;
    for (size_t i = 0; i < names.size() && i < 20; ++i) list += (i ? ", " : "") + names[i];
    if (names.size() > 20) list += fmt::format(", ... ({} more)", names.size() - 20);
    throw InputError(
        where_file, where_field,
        fmt::format("{}no node or mesh named '{}' (available: {})", what, mesh_name, list));
  }
  Mesh mesh = builder.finish();
  if (mesh.triangles.empty())
    throw NoSurfaceError(where_file, where_field, what + "contains no triangles");
  mesh.id = mesh_name.empty() ? fs::path(path).stem().string() : mesh_name;
  mesh.source.kind = MeshSource::Kind::File;
  mesh.source.file = path;
  mesh.source.scale = scale;
  mesh.source.up = up;
  mesh.source.mesh_name = mesh_name;
  return mesh;
}

}  // namespace inet
