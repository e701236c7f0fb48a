#pragma once
// Small text helpers for readers and messages.
#include <string>
#include <vector>

namespace inet {

/// The non-empty items of a comma list ("rgb,depth,,label" -> rgb, depth, label).
std::vector<std::string> splitCommaList(const std::string& list);
/// The items joined with commas, the inverse of splitCommaList.
std::string joinCommaList(const std::vector<std::string>& items);

/// The fields of `line` between runs of spaces and tabs.
std::vector<std::string> splitWhitespace(const std::string& line);

/// "a, b, c" of the first `most` names, then ", ... (N more)": one warning line names what it
/// counts without growing with the file.
std::string listNames(const std::vector<std::string>& names, size_t most = 8);

/// `s` with ASCII letters in lower case.
std::string lowerCase(std::string s);

/// The file name's extension in lower case, with its dot (".obj", ".glb"), "" if none.
std::string lowerExtension(const std::string& path);

}  // namespace inet
