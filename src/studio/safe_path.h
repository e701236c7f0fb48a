#pragma once
// Resolving a request path to a file below a folder the studio was given, and nothing else.
//
// The studio serves its own web assets and read-only files from a few named folders (the
// layout's folder, an output folder). A request names a file by a URL path relative to such a
// root; resolveBelowRoot() is the only way from that text to a file on disk. Its rules:
//  1. the text is percent-decoded exactly once (the caller passes the raw, still-encoded path,
//     so "%2e%2e" is seen as ".." here and "%252e" stays the literal "%2e");
//  2. refused: a malformed escape, a NUL byte or other control character, a backslash, a
//     leading '/' (an absolute path), a ".." component, and any component starting with '.'
//     (hidden files such as .git or .ssh are never served);
//  3. the root and the candidate are made canonical (every symlink followed); the candidate must
//     exist, be a regular file, and lie inside the canonical root component by component (so a
//     symlink inside the root that points out of it is refused, and "/data2" is not inside
//     "/data").
// A root that is itself a symlink is resolved once, when the server starts (see the server).
// The check and the later open are separate steps: a user who swaps a symlink inside their own
// data folder between the two can still point it elsewhere. The roots are the user's own
// folders, and the server only reads; docs/studio.md says so.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace inet::studio {

/// Why a path was refused. The client sees only 403 (a refused path) or 404 (no such file);
/// the reason is for tests and the server's log.
enum class PathRefusal {
  None,         ///< accepted
  BadEncoding,  ///< malformed %-escape, or a control character after decoding
  NulByte,      ///< a NUL byte (raw or %00)
  Backslash,    ///< a '\' (Windows separators are never path syntax here)
  Absolute,     ///< starts with '/', i.e. names a path from the file system's root
  DotDot,       ///< a ".." component
  Hidden,       ///< a component starting with '.'
  OutsideRoot,  ///< exists, but its canonical path (symlinks followed) leaves the root
  NotFound,     ///< no such regular file (or the root itself is missing)
};
const char* pathRefusalName(PathRefusal r);

/// The outcome of resolveBelowRoot: the canonical file path when accepted.
struct ResolvedPath {
  std::filesystem::path path;
  PathRefusal refusal = PathRefusal::None;
  bool ok() const { return refusal == PathRefusal::None; }
  /// 403 for a refused path, 404 for a missing file, 200 when accepted.
  int httpStatus() const;
};

/// Percent-decodes `in` ("%41" -> "A"; '+' stays '+'). Nullopt for a '%' not followed by two
/// hex digits.
std::optional<std::string> percentDecode(std::string_view in);

/// Resolves `encoded`, a URL path relative to `root` (still percent-encoded, no query string),
/// by the rules above. Pure apart from reading the file system's metadata.
ResolvedPath resolveBelowRoot(const std::filesystem::path& root, std::string_view encoded);

/// Is `p` equal to `root` or below it, comparing whole components? Both should be canonical.
bool isWithin(const std::filesystem::path& p, const std::filesystem::path& root);

/// The Content-Type for a file served by name: html, js, css, json, png, jpg, svg, glb, gltf,
/// bin, txt; everything else (exr included) application/octet-stream.
std::string contentTypeFor(const std::filesystem::path& file);

}  // namespace inet::studio
