#pragma once
// A TOML file as the scene readers see it: parsed, `--set` overrides merged into the tree, then read section
// by section through typed getters that record the keys asked for (a key nobody asked for is an "unknown
// key" error: a typo must never be silently ignored). Every problem is a SceneError "<source>: <key>:
// <problem>". toml++ is heavy to compile: toml_document.cpp is the library's only file that includes it;
// the spreader's scene (scene_parser.cpp) and the drum's (libspread/physics/drum/drum_scene.cpp) read through this.
#include <cstdint>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace spread::scene {

// One TOML table (a section, or one element of an array of tables). Absent sections read as empty.
// Valid while its TomlDocument lives.
class TomlSection {
 public:
  TomlSection(const void* table, std::string path, std::string source);

  // "<path>.<key>" (or the key alone at the top level).
  std::string key_path(const std::string& key) const;
  [[noreturn]] void fail(const std::string& key, const std::string& problem) const;
  // Whether the file (or an override) sets the key, as opposed to leaving it at its default.
  bool present(const std::string& key) const;

  // Each getter records the key as known; nullopt when the key is absent; SceneError for a wrong type.
  std::optional<double> number(const std::string& key);  // finite; an integer is accepted
  std::optional<std::int64_t> integer(const std::string& key);
  std::optional<bool> boolean(const std::string& key);
  std::optional<std::string> string(const std::string& key);
  std::optional<std::vector<double>> numbers(const std::string& key);
  std::optional<std::vector<std::string>> strings(const std::string& key);
  // An array of tables inside this one (`[[materials.components]]`, or an array of inline tables), each a
  // section named "<path>.<key>[i]"; empty when the key is absent.
  std::vector<TomlSection> tables(const std::string& key);

  // Every key of the table must have been asked for.
  void finish() const;

  const std::string& source() const { return source_; }

 private:
  const void* table_;  // const toml::table*, or nullptr for an absent section
  std::string path_;
  std::string source_;
  std::set<std::string> used_;
};

class TomlDocument {
 public:
  // Parses `text` (syntax errors give "<source>:<line>:<column>: …") and merges the overrides
  // "dotted.key=value" into the tree: the value is TOML, a bare word that is not valid TOML is taken as a
  // string, array elements by index ("materials.0.density_kg_m3=1800").
  TomlDocument(const std::string& text, const std::string& source_name, const std::vector<std::string>& overrides);
  ~TomlDocument();
  TomlDocument(const TomlDocument&) = delete;
  TomlDocument& operator=(const TomlDocument&) = delete;

  const std::string& source_name() const { return source_; }
  // A top-level key outside `known` is an "unknown key" error.
  void check_top_level_keys(const std::set<std::string>& known) const;
  bool has(const std::string& key) const;
  // The table [key] (empty when absent); SceneError when the key is not a table.
  TomlSection section(const std::string& key) const;
  // The tables of [[key]], path "key[i]" (none when absent); SceneError when not an array of tables.
  std::vector<TomlSection> array_of_tables(const std::string& key) const;

 private:
  struct Tree;
  std::unique_ptr<Tree> tree_;
  std::string source_;
};

// The text of a scene file, or SceneError "<path>: cannot open the scene file".
std::string read_scene_text(const std::string& path);

}  // namespace spread::scene
