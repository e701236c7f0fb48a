#include "scene/obj_prepass.h"

#include <charconv>
#include <filesystem>
#include <map>
#include <set>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/text.h"

namespace fs = std::filesystem;

namespace inet {
namespace {

std::vector<std::string> splitLines(const std::string& text) {
  std::vector<std::string> out;
  size_t pos = 0;
  while (pos < text.size()) {
    size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    std::string l = text.substr(pos, end - pos);
    if (!l.empty() && l.back() == '\r') l.pop_back();
    out.push_back(std::move(l));
    pos = end + 1;
  }
  return out;
}

/// ".5" -> "0.5", "-.5" -> "-0.5"; true if changed.
bool fixLeadingDot(std::string& tok) {
  const size_t sign = !tok.empty() && (tok[0] == '-' || tok[0] == '+') ? 1 : 0;
  if (tok.size() > sign + 1 && tok[sign] == '.' && tok[sign + 1] >= '0' && tok[sign + 1] <= '9') {
    tok.insert(sign, "0");
    return true;
  }
  return false;
}

/// Checks one index of a face corner against the `count` elements read so far (OBJ: 1-based,
/// negative = relative to the end). Empty = not given.
void checkIndex(const std::string& s, int64_t count, const char* what, const char* plural,
                const std::string& path, int line_no) {
  if (s.empty()) return;
  int64_t v = 0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  const auto fail = [&](const std::string& why) {
    throw InputError(path, fmt::format("line {}", line_no), why);
  };
  if (ec != std::errc() || ptr != s.data() + s.size())
    fail(fmt::format("face index '{}' is not a whole number", s));
  if (v == 0) fail(fmt::format("face {} index 0 (OBJ counts from 1)", what));
  if (v > count || -v > count)
    fail(fmt::format("face {} index {} but only {} {} come before it", what, v, count,
                     count == 1 ? what : plural));
}

/// Is a face corner's index (not empty) within the `count` elements read so far?
bool indexInRange(const std::string& s, int64_t count) {
  int64_t v = 0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || ec != std::errc() || ptr != s.data() + s.size()) return true;  // checked later
  return v != 0 && v <= count && -v <= count;
}

}  // namespace

ObjPrepass prepassObj(const std::string& path) {
  const std::string text = readTextFile(path);
  ObjPrepass out;
  std::string rewritten;
  rewritten.reserve(text.size() + 64);
  int64_t nv = 0, nvt = 0, nvn = 0;
  std::vector<std::string> libs;
  std::vector<std::string> used;
  std::set<std::string> used_seen;
  // the last line that declares each group name (`g NAME`; `o NAME` too, as Assimp reads it)
  // (a scan of the line starts only: the file's other lines are not split twice)
  std::map<std::string, int> last_declared;
  int n = 1;
  for (size_t at = 0; at < text.size(); ++n) {
    const size_t first = text.find_first_not_of(" \t", at);
    const size_t end = std::min(text.find('\n', at), text.size());
    if (first < end && (text[first] == 'g' || text[first] == 'o')) {
      const size_t stop = text[end - 1] == '\r' ? end - 1 : end;  // CRLF
      const std::vector<std::string> t = splitWhitespace(text.substr(first, stop - first));
      if (t.size() == 2 && (t[0] == "g" || t[0] == "o")) last_declared[t[1]] = n;
    }
    at = end + 1;
  }
  std::string group;  // the current group's name
  size_t pos = 0;
  int line_no = 0;
  while (pos < text.size()) {
    size_t end = text.find('\n', pos);
    const size_t next = end == std::string::npos ? text.size() : end + 1;
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(pos, end - pos);
    const std::string eol = text.substr(end, next - end);
    pos = next;
    ++line_no;
    const bool cr = !line.empty() && line.back() == '\r';
    if (cr) line.pop_back();
    std::vector<std::string> tok = splitWhitespace(line);
    bool changed = false;
    if (!tok.empty()) {
      const std::string& key = tok[0];
      if (key == "v" || key == "vt" || key == "vn") {
        (key == "v" ? nv : key == "vt" ? nvt : nvn) += 1;
        if (key == "v" && tok.size() == 5) {  // x y z w (7 values would be x y z r g b)
          tok.pop_back();
          ++out.w_values;
          changed = true;
        }
        for (size_t k = 1; k < tok.size(); ++k)
          if (fixLeadingDot(tok[k])) ++out.leading_dots, changed = true;
      } else if (key == "f") {
        for (size_t k = 1; k < tok.size(); ++k) {
          const std::string& c = tok[k];
          const size_t a = c.find('/');
          const size_t b = a == std::string::npos ? std::string::npos : c.find('/', a + 1);
          checkIndex(c.substr(0, a), nv, "vertex", "vertices", path, line_no);
          if (a != std::string::npos)
            checkIndex(c.substr(a + 1, b == std::string::npos ? std::string::npos : b - a - 1),
                       nvt, "texture coordinate", "texture coordinates", path, line_no);
          if (b == std::string::npos) continue;
          if (!indexInRange(c.substr(b + 1), nvn)) {
            // a normal that is not there (Sweet Home 3D's own window models: `f 108 107 98
            // 81//125` in a file without `vn`): that corner is shaded without it, as Sweet
            // Home 3D's reader does, instead of failing the file
            tok[k] = c.substr(0, b == a + 1 ? a : b);
            ++out.missing_normals;
            changed = true;
            continue;
          }
          checkIndex(c.substr(b + 1), nvn, "normal", "normals", path, line_no);
        }
        if (tok.size() < 4) {  // `f a b`: an edge, which Assimp keeps as a malformed face
          tok[0] = "l";
          for (size_t k = 1; k < tok.size(); ++k) tok[k] = tok[k].substr(0, tok[k].find('/'));
          ++out.line_faces;
          changed = true;
        }
      } else if (key == "mtllib" && tok.size() > 1) {
        libs.push_back(line.substr(line.find("mtllib") + 6));
        const size_t f = libs.back().find_first_not_of(" \t");
        libs.back() = f == std::string::npos ? "" : libs.back().substr(f);
      } else if (key == "g" || key == "o") {
        group = tok.size() == 2 ? tok[1] : "";
      } else if (key == "usemtl" && tok.size() > 1) {
        if (used_seen.insert(tok[1]).second) used.push_back(tok[1]);
        const auto later = last_declared.find(tok[1]);
        if (tok.size() == 2 && group != tok[1] && later != last_declared.end() &&
            later->second > line_no) {
          rewritten += "g " + tok[1] + (cr ? "\r" : "") + (eol.empty() ? "\n" : eol);
          group = tok[1];
          ++out.late_groups;
        }
      }
    }
    if (changed) {
      std::string joined;
      for (size_t k = 0; k < tok.size(); ++k) joined += (k ? " " : "") + tok[k];
      rewritten += joined + (cr ? "\r" : "") + eol;
    } else {
      rewritten += line + (cr ? "\r" : "") + eol;
    }
  }
  if (out.w_values > 0 || out.leading_dots > 0 || out.late_groups > 0 || out.line_faces > 0 ||
      out.missing_normals > 0)
    out.text = std::move(rewritten);
  // material libraries: a name with spaces is one file or several (tinyobjloader reads both)
  std::set<std::string> defined;
  const fs::path dir = fs::path(path).parent_path();
  bool any_library = false;
  for (const std::string& lib : libs) {
    std::vector<fs::path> files;
    std::error_code ec;
    if (fs::is_regular_file(dir / lib, ec)) {
      files.push_back(dir / lib);
    } else {
      for (const std::string& part : splitWhitespace(lib))
        if (fs::is_regular_file(dir / part, ec)) files.push_back(dir / part);
      if (files.empty()) out.missing_mtllibs.push_back(lib);
    }
    for (const fs::path& f : files) {
      any_library = true;
      for (const std::string& l : splitLines(readTextFile(f))) {
        const std::vector<std::string> t = splitWhitespace(l);
        if (t.size() > 1 && t[0] == "newmtl") defined.insert(t[1]);
      }
    }
  }
  if (!any_library || !out.missing_mtllibs.empty())
    for (const std::string& name : used)
      if (!defined.count(name)) out.grey_materials.push_back(name);
  return out;
}

}  // namespace inet
