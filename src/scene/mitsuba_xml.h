#pragma once
// The XML layer of the Mitsuba scene importer (mitsuba_importer.h): a scene file read into a
// pugixml tree with Mitsuba's own conventions resolved, and typed access to plugin properties.
// Internal to src/scene: only the importer's files include it.
//
// What it resolves, for Mitsuba 0.4-0.6 and Mitsuba 2/3 files alike:
//  - the version: <scene version="..."> is required (as Mitsuba does); majors 0, 2 and 3 read;
//  - parameters: <default name="spp" value="64"/> and `$spp` anywhere in an attribute value
//    (values given to the importer override the defaults, as Mitsuba's -D does);
//  - <include filename="..."/> at the top level (relative to the including file);
//  - property names in either spelling: 0.6's camelCase ("toWorld", "intIOR") is read as
//    Mitsuba 3's snake_case ("to_world", "int_ior"), so converters ask for one name;
//  - <ref id="..."/> and <ref name="..." id="..."/>, resolved against every id of the file;
//  - transforms: <matrix>, <translate>, <rotate>, <scale>, <lookat>, in either attribute style
//    (x="1" y="2" or value="1 2"), composed in file order (each new one on the left).
// Every failure is an InputError(file, "line N <tag ...>", problem).
#include <pugixml.hpp>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace inet::mitsuba {

/// "toWorld" -> "to_world", "intIOR" -> "int_ior", "fov_axis" unchanged.
std::string snakeCase(const std::string& name);

/// Findings worth a warning, each kept once with the names of everything it applies to.
class Notes {
 public:
  /// Records that `what` happened to `subject` (e.g. "roughplastic 'nonlinear' ignored", "Floor").
  void add(const std::string& what, const std::string& subject);
  /// One line per finding in first-seen order: "what (3: Floor, TableWood, Paneling)".
  std::vector<std::string> lines() const;

 private:
  std::vector<std::pair<std::string, std::vector<std::string>>> items_;
};

/// A parsed scene file with its includes.
class Document {
 public:
  /// Parses `text`; `path` names it in errors and is the base of relative file names.
  /// `parameters` override the file's <default> values. Includes are read from disk only when
  /// `read_includes` (otherwise they are skipped and noted).
  Document(const std::string& text, const std::string& path,
           const std::map<std::string, std::string>& parameters, bool read_includes,
           Notes& notes);
  ~Document();
  Document(const Document&) = delete;
  Document& operator=(const Document&) = delete;

  /// The scene's top-level elements, includes expanded in place, in file order.
  const std::vector<pugi::xml_node>& topLevel() const { return top_level_; }
  /// Major version of the main file: 0 (Mitsuba 0.x), 2 or 3.
  int majorVersion() const { return major_; }
  /// The element with attribute id="id", or an empty node.
  pugi::xml_node byId(const std::string& id) const;

  /// The file `node` came from, and the folder its relative file names start from.
  const std::string& fileOf(pugi::xml_node node) const;
  std::string folderOf(pugi::xml_node node) const;
  /// "line 12 <bsdf type="diffuse" id="Floor">": where `node` is, for messages.
  std::string where(pugi::xml_node node) const;
  [[noreturn]] void fail(pugi::xml_node node, const std::string& problem) const;

  /// Property bookkeeping: which elements a converter has read.
  void markUsed(pugi::xml_node node) const;
  bool used(pugi::xml_node node) const;

 private:
  struct Source;
  const Source& load(const std::string& text, const std::string& path);
  void expand(const Source& src, int depth, bool read_includes, Notes& notes);
  void substitute(pugi::xml_node node, const Source& src) const;
  void indexIds();
  const Source* sourceOf(pugi::xml_node node) const;

  std::vector<std::unique_ptr<Source>> sources_;
  std::map<std::string, std::string> parameters_;
  std::vector<pugi::xml_node> top_level_;
  std::map<std::string, pugi::xml_node> ids_;
  mutable std::vector<const void*> used_;  // sorted internal_object() pointers
  int major_ = 0;
};

class Plugin;

/// A colour-or-texture property: a constant (the fallback when absent) or a texture plugin.
struct Slot {
  bool given = false;
  Vec3f value = Vec3f::Zero();
  std::shared_ptr<Plugin> texture;  ///< set when the property is a texture (nested or <ref>)
};

/// Typed access to one plugin element (<bsdf>, <shape>, <emitter>, <sensor>, <texture>, ...).
/// Every accessor marks the property it read as used; unused() lists the rest. Accessors take
/// snake_case names and accept both spellings in the file.
class Plugin {
 public:
  Plugin(const Document& doc, pugi::xml_node node) : doc_(&doc), node_(node) {}

  pugi::xml_node node() const { return node_; }
  const Document& doc() const { return *doc_; }
  std::string tag() const { return node_.name(); }
  std::string type() const { return node_.attribute("type").value(); }
  std::string id() const { return node_.attribute("id").value(); }
  std::string where() const { return doc_->where(node_); }
  [[noreturn]] void fail(const std::string& problem) const { doc_->fail(node_, problem); }

  /// Is a property of this name given (not marked used)?
  bool has(const std::string& name) const { return static_cast<bool>(find(name, false)); }
  /// The element tag of property `name` ("float", "string", "texture", ...), "" when absent.
  std::string kind(const std::string& name) const { return find(name, false).name(); }
  /// Marks a property as read without reading it (settings that change nothing here).
  void ignore(const std::string& name) const { find(name, true); }
  double number(const std::string& name, double fallback) const;  ///< <float> or <integer>
  int integer(const std::string& name, int fallback) const;
  bool boolean(const std::string& name, bool fallback) const;
  std::string string(const std::string& name, const std::string& fallback) const;
  /// A <vector> or <point> (x/y/z attributes or value="x, y, z").
  Vec3 vector(const std::string& name, const Vec3& fallback) const;
  /// A <transform> (identity when absent).
  Mat4 transform(const std::string& name) const;
  /// A colour (<rgb>, <srgb>, <spectrum>, <float>, <blackbody>) or texture property.
  /// Spectra given as wavelength:value pairs are converted to RGB through the CIE 1931
  /// matching functions; a spectrum file cannot be read and gives the fallback (noted).
  Slot slot(const std::string& name, const Vec3f& fallback, Notes& notes) const;
  /// The nested plugins with this tag (element or <ref> to one), in file order.
  std::vector<Plugin> children(const std::string& tag) const;
  /// Names of the properties nothing has read.
  std::vector<std::string> unused() const;

 private:
  pugi::xml_node find(const std::string& name, bool mark) const;
  pugi::xml_node resolve(pugi::xml_node ref) const;  // <ref> -> its target
  const Document* doc_;
  pugi::xml_node node_;
};

/// Mitsuba's named indices of refraction ("bk7", "water", ...); nullopt for an unknown name.
std::optional<double> namedIor(const std::string& name);
/// The names namedIor knows, for messages.
std::string namedIorList();

}  // namespace inet::mitsuba
