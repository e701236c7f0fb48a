#pragma once
// Java .properties files (java.util.Properties.load), the format of Sweet Home 3D's catalogs
// (PluginFurnitureCatalog.properties inside a .sh3f).
//
// Why hand-written: no Debian C++ library reads this format, and its rules are short: bytes
// are ISO-8859-1; '#' or '!' starts a comment line; a key ends at the first unescaped '=', ':'
// or white space; a line ending in an odd number of backslashes continues on the next one
// (whose leading white space is dropped); escapes \t \n \r \f \uXXXX, and '\' before any other
// character stands for that character. Later keys replace earlier ones, as in Java.
#include <map>
#include <string>
#include <string_view>

namespace inet {

/// Key -> value, both converted to UTF-8.
using JavaProperties = std::map<std::string, std::string>;

/// Parses the text of a .properties file. Throws InputError(where, "line N", ...) for a
/// malformed \u escape, the only error the format has.
JavaProperties parseJavaProperties(std::string_view text, const std::string& where);

}  // namespace inet
