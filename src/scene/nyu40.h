#pragma once
// The NYU40 label set (Gupta et al., CVPR 2013): ids 1..40, 0 = void / unlabelled.
#include <optional>
#include <string>
#include <string_view>

namespace inet {

constexpr int kNyu40Count = 41;  ///< ids 0..40

/// Canonical snake_case name of an id (0 -> "void"); "" if out of range.
std::string_view nyu40Name(int id);
/// Id of a class name. Case, spaces, '-' and '_' are ignored ("Night stand" == "night_stand"),
/// and the common spellings "refrigerator"/"refridgerator" both work.
std::optional<int> nyu40FromName(std::string_view name);
/// A distinct display colour per class (for previews), RGB 0..255.
void nyu40Color(int id, unsigned char rgb[3]);

}  // namespace inet
