#include "studio/safe_path.h"

#include <algorithm>
#include <cctype>
#include <map>
#include <vector>

namespace inet::studio {

namespace fs = std::filesystem;

const char* pathRefusalName(PathRefusal r) {
  switch (r) {
    case PathRefusal::None:
      return "accepted";
    case PathRefusal::BadEncoding:
      return "malformed escape or control character";
    case PathRefusal::NulByte:
      return "NUL byte";
    case PathRefusal::Backslash:
      return "backslash";
    case PathRefusal::Absolute:
      return "absolute path";
    case PathRefusal::DotDot:
      return "'..' component";
    case PathRefusal::Hidden:
      return "hidden component";
    case PathRefusal::OutsideRoot:
      return "outside the root";
    case PathRefusal::NotFound:
      return "no such file";
  }
  return "?";
}

int ResolvedPath::httpStatus() const {
  if (ok()) return 200;
  return refusal == PathRefusal::NotFound ? 404 : 403;
}

std::optional<std::string> percentDecode(std::string_view in) {
  auto hex = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
  };
  std::string out;
  out.reserve(in.size());
  for (size_t i = 0; i < in.size(); ++i) {
    if (in[i] != '%') {
      out.push_back(in[i]);
      continue;
    }
    if (i + 2 >= in.size()) return std::nullopt;  // needs two more characters
    const int hi = hex(in[i + 1]), lo = hex(in[i + 2]);
    if (hi < 0 || lo < 0) return std::nullopt;
    out.push_back(static_cast<char>(hi * 16 + lo));
    i += 2;
  }
  return out;
}

bool isWithin(const fs::path& p, const fs::path& root) {
  // component-wise prefix: "/data2/x" is not within "/data"
  auto r = root.begin(), q = p.begin();
  for (; r != root.end(); ++r, ++q) {
    if (r->empty() && std::next(r) == root.end()) return true;  // a root ending in '/'
    if (q == p.end() || *q != *r) return false;
  }
  return true;
}

namespace {

/// The lexical checks (rules 1 and 2); fills `components` with the decoded path's parts.
PathRefusal checkText(std::string_view encoded, std::vector<std::string>& components) {
  // a raw NUL is refused before decoding too (std::string carries it, the file system would not)
  if (encoded.find('\0') != std::string_view::npos) return PathRefusal::NulByte;
  const std::optional<std::string> decoded = percentDecode(encoded);
  if (!decoded) return PathRefusal::BadEncoding;
  const std::string& s = *decoded;
  if (s.find('\0') != std::string::npos) return PathRefusal::NulByte;
  if (std::any_of(s.begin(), s.end(),
                  [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; }))
    return PathRefusal::BadEncoding;
  if (s.find('\\') != std::string::npos) return PathRefusal::Backslash;
  if (!s.empty() && s.front() == '/') return PathRefusal::Absolute;
  size_t start = 0;
  while (start <= s.size()) {
    const size_t end = std::min(s.find('/', start), s.size());
    std::string part = s.substr(start, end - start);
    if (part == "..") return PathRefusal::DotDot;
    if (!part.empty() && part.front() == '.') return PathRefusal::Hidden;
    if (!part.empty()) components.push_back(std::move(part));
    start = end + 1;
  }
  return PathRefusal::None;
}

}  // namespace

ResolvedPath resolveBelowRoot(const fs::path& root, std::string_view encoded) {
  std::vector<std::string> components;
  if (PathRefusal r = checkText(encoded, components); r != PathRefusal::None) return {{}, r};
  std::error_code ec;
  const fs::path canonical_root = fs::canonical(root, ec);
  if (ec || !fs::is_directory(canonical_root, ec)) return {{}, PathRefusal::NotFound};
  fs::path candidate = canonical_root;
  for (const std::string& c : components) candidate /= c;
  // canonical() follows every symlink and fails when something along the way is missing
  const fs::path resolved = fs::canonical(candidate, ec);
  if (ec) return {{}, PathRefusal::NotFound};
  if (!isWithin(resolved, canonical_root)) return {{}, PathRefusal::OutsideRoot};
  if (!fs::is_regular_file(resolved, ec)) return {{}, PathRefusal::NotFound};
  return {resolved, PathRefusal::None};
}

std::string contentTypeFor(const fs::path& file) {
  static const std::map<std::string, std::string> kTypes = {
      {".html", "text/html; charset=utf-8"},
      {".htm", "text/html; charset=utf-8"},
      {".js", "text/javascript; charset=utf-8"},
      {".mjs", "text/javascript; charset=utf-8"},
      {".css", "text/css; charset=utf-8"},
      {".json", "application/json"},
      {".png", "image/png"},
      {".jpg", "image/jpeg"},
      {".jpeg", "image/jpeg"},
      {".svg", "image/svg+xml"},
      {".glb", "model/gltf-binary"},
      {".gltf", "model/gltf+json"},
      {".bin", "application/octet-stream"},
      {".txt", "text/plain; charset=utf-8"},
      {".csv", "text/csv; charset=utf-8"},
  };
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  const auto it = kTypes.find(ext);
  return it == kTypes.end() ? "application/octet-stream" : it->second;
}

}  // namespace inet::studio
