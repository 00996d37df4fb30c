// TOML text → tree with the overrides merged → typed reads that record the keys asked for
// (toml_document.hpp). The library's only toml++ user.
#include "libspread/io/scene/toml_document.hpp"

#include <toml++/toml.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "libspread/io/scene/scene.hpp"
#include "libspread/io/scene/scene_key.hpp"

namespace spread::scene {
namespace {

// ---- overrides -------------------------------------------------------------------------------------

bool is_bare_key_segment(const std::string& segment) {
  if (segment.empty()) return false;
  for (char c : segment) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
    if (!ok) return false;
  }
  return true;
}

std::string quote_toml_string(const std::string& raw) {
  std::string out = "\"";
  for (char c : raw) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

bool is_index(const std::string& key) {
  return !key.empty() && key.find_first_not_of("0123456789") == std::string::npos;
}

// Puts `value` at `key` of `dest`; tables merge key by key, arrays take integer keys as indices.
void merge_node(toml::table& dest, const std::string& key, toml::node& value, const std::string& where);

void merge_into_array(toml::array& dest, toml::table& indices, const std::string& where) {
  for (auto&& [index_key, value] : indices) {
    const std::string index_text(index_key.str());
    const std::string path = where + "." + index_text;
    if (!is_index(index_text)) throw SceneError(path + ": expected an array index");
    // from_chars, not stoul: an index too long for size_t is out of range too, not an exception
    // escaping the parser (found by fuzz_scene_parser: materials.888888888888888888888881.…).
    std::size_t index = 0;
    const auto [end, error] = std::from_chars(index_text.data(), index_text.data() + index_text.size(), index);
    if (error != std::errc() || end != index_text.data() + index_text.size() || index >= dest.size()) {
      throw SceneError(path + ": index out of range (the array has " + std::to_string(dest.size()) + " elements)");
    }
    toml::node& element = *dest.get(index);
    if (auto* element_table = element.as_table(); element_table != nullptr && value.is_table()) {
      for (auto&& [k, v] : *value.as_table()) merge_node(*element_table, std::string(k.str()), v, path);
    } else {
      value.visit([&](auto&& concrete) { dest.replace(dest.cbegin() + static_cast<std::ptrdiff_t>(index), std::move(concrete)); });
    }
  }
}

void merge_node(toml::table& dest, const std::string& key, toml::node& value, const std::string& where) {
  const std::string path = where.empty() ? key : where + "." + key;
  toml::node* existing = dest.get(key);
  if (existing != nullptr && existing->is_table() && value.is_table()) {
    for (auto&& [k, v] : *value.as_table()) merge_node(*existing->as_table(), std::string(k.str()), v, path);
    return;
  }
  if (existing != nullptr && existing->is_array() && value.is_table()) {
    merge_into_array(*existing->as_array(), *value.as_table(), path);
    return;
  }
  value.visit([&](auto&& concrete) { dest.insert_or_assign(key, std::move(concrete)); });
}

void apply_override(toml::table& root, const std::string& assignment, const std::string& source) {
  const std::size_t equals = assignment.find('=');
  if (equals == std::string::npos || equals == 0) {
    throw SceneError(source + ": --set " + assignment + ": expected key=value");
  }
  const std::string key = assignment.substr(0, equals);
  const std::string value = assignment.substr(equals + 1);
  std::stringstream segments(key);
  for (std::string segment; std::getline(segments, segment, '.');) {
    if (!is_bare_key_segment(segment)) throw SceneError(source + ": --set " + key + ": not a dotted key");
  }
  if (key.back() == '.') throw SceneError(source + ": --set " + key + ": not a dotted key");
  toml::table parsed;
  try {
    parsed = toml::parse(key + " = " + value);
  } catch (const toml::parse_error&) {
    try {  // a bare word: take it as a string (`--set simulate.material=Urea`)
      parsed = toml::parse(key + " = " + quote_toml_string(value));
    } catch (const toml::parse_error& e) {
      throw SceneError(source + ": --set " + key + ": cannot parse value: " + std::string(e.description()));
    }
  }
  try {
    for (auto&& [k, v] : parsed) merge_node(root, std::string(k.str()), v, "");
  } catch (const SceneError& e) {
    throw SceneError(source + ": --set " + assignment + ": " + e.what());
  }
}

const toml::table* as_table(const void* table) { return static_cast<const toml::table*>(table); }

const char* type_name(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::table: return "a table";
    case toml::node_type::array: return "an array";
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a number";
    case toml::node_type::boolean: return "a boolean";
    default: return "a date/time";
  }
}

}  // namespace

// ---- typed reading with unknown-key detection ------------------------------------------------------

TomlSection::TomlSection(const void* table, std::string path, std::string source)
    : table_(table), path_(std::move(path)), source_(std::move(source)) {}

std::string TomlSection::key_path(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

void TomlSection::fail(const std::string& key, const std::string& problem) const {
  throw SceneError(source_ + ": " + key_path(key) + ": " + problem);
}

bool TomlSection::present(const std::string& key) const {
  return table_ != nullptr && as_table(table_)->get(key) != nullptr;
}

namespace {

// The node at `key`, recorded as asked for; nullptr when absent.
const toml::node* lookup(const void* table, std::set<std::string>& used, const std::string& key) {
  used.insert(key);
  return table != nullptr ? as_table(table)->get(key) : nullptr;
}

}  // namespace

std::optional<double> TomlSection::number(const std::string& key) {
  const toml::node* node = lookup(table_, used_, key);
  if (node == nullptr) return std::nullopt;
  if (const auto* f = node->as_floating_point()) {
    const double value = f->get();
    if (!std::isfinite(value)) fail(key, "must be a finite number, got " + format_number(value));
    return value;
  }
  if (const auto* i = node->as_integer()) return static_cast<double>(i->get());
  fail(key, std::string("expected a number, got ") + type_name(*node));
}

std::optional<std::int64_t> TomlSection::integer(const std::string& key) {
  const toml::node* node = lookup(table_, used_, key);
  if (node == nullptr) return std::nullopt;
  if (const auto* i = node->as_integer()) return i->get();
  fail(key, std::string("expected an integer, got ") + type_name(*node));
}

std::optional<bool> TomlSection::boolean(const std::string& key) {
  const toml::node* node = lookup(table_, used_, key);
  if (node == nullptr) return std::nullopt;
  if (const auto* b = node->as_boolean()) return b->get();
  fail(key, std::string("expected true or false, got ") + type_name(*node));
}

std::optional<std::string> TomlSection::string(const std::string& key) {
  const toml::node* node = lookup(table_, used_, key);
  if (node == nullptr) return std::nullopt;
  if (const auto* s = node->as_string()) return s->get();
  fail(key, std::string("expected a string, got ") + type_name(*node));
}

std::optional<std::vector<double>> TomlSection::numbers(const std::string& key) {
  const toml::node* node = lookup(table_, used_, key);
  if (node == nullptr) return std::nullopt;
  const toml::array* array = node->as_array();
  if (array == nullptr) fail(key, std::string("expected an array of numbers, got ") + type_name(*node));
  std::vector<double> values;
  for (std::size_t i = 0; i < array->size(); ++i) {
    const toml::node& element = *array->get(i);
    const std::string element_key = key + "[" + std::to_string(i) + "]";
    if (const auto* f = element.as_floating_point()) {
      if (!std::isfinite(f->get())) fail(element_key, "must be a finite number, got " + format_number(f->get()));
      values.push_back(f->get());
    } else if (const auto* n = element.as_integer()) {
      values.push_back(static_cast<double>(n->get()));
    } else {
      fail(element_key, std::string("expected a number, got ") + type_name(element));
    }
  }
  return values;
}

std::optional<std::vector<std::string>> TomlSection::strings(const std::string& key) {
  const toml::node* node = lookup(table_, used_, key);
  if (node == nullptr) return std::nullopt;
  const toml::array* array = node->as_array();
  if (array == nullptr) fail(key, std::string("expected an array of strings, got ") + type_name(*node));
  std::vector<std::string> values;
  for (std::size_t i = 0; i < array->size(); ++i) {
    const auto* s = array->get(i)->as_string();
    if (s == nullptr) fail(key + "[" + std::to_string(i) + "]", "expected a string");
    values.push_back(s->get());
  }
  return values;
}

std::vector<TomlSection> TomlSection::tables(const std::string& key) {
  std::vector<TomlSection> sections;
  const toml::node* node = lookup(table_, used_, key);
  if (node == nullptr) return sections;
  const toml::array* array = node->as_array();
  if (array == nullptr) fail(key, std::string("expected an array of tables, got ") + type_name(*node));
  for (std::size_t i = 0; i < array->size(); ++i) {
    const std::string element_key = key + "[" + std::to_string(i) + "]";
    const toml::table* table = array->get(i)->as_table();
    if (table == nullptr) fail(element_key, std::string("expected a table, got ") + type_name(*array->get(i)));
    sections.emplace_back(table, key_path(element_key), source_);
  }
  return sections;
}

void TomlSection::finish() const {
  if (table_ == nullptr) return;
  for (auto&& [key, value] : *as_table(table_)) {
    const std::string name(key.str());
    if (used_.count(name) == 0) fail(name, "unknown key");
  }
}

// ---- the document ----------------------------------------------------------------------------------

struct TomlDocument::Tree {
  toml::table root;
};

TomlDocument::TomlDocument(const std::string& text, const std::string& source_name,
                           const std::vector<std::string>& overrides)
    : tree_(std::make_unique<Tree>()), source_(source_name) {
  try {
    tree_->root = toml::parse(text, source_name);
  } catch (const toml::parse_error& e) {
    throw SceneError(source_name + ":" + std::to_string(e.source().begin.line) + ":" +
                     std::to_string(e.source().begin.column) + ": " + std::string(e.description()));
  }
  for (const std::string& assignment : overrides) apply_override(tree_->root, assignment, source_name);
}

TomlDocument::~TomlDocument() = default;

void TomlDocument::check_top_level_keys(const std::set<std::string>& known) const {
  for (auto&& [key, value] : tree_->root) {
    const std::string name(key.str());
    if (known.count(name) == 0) throw SceneError(source_ + ": " + name + ": unknown key");
  }
}

bool TomlDocument::has(const std::string& key) const { return tree_->root.get(key) != nullptr; }

TomlSection TomlDocument::section(const std::string& key) const {
  const toml::node* node = tree_->root.get(key);
  if (node != nullptr && !node->is_table()) throw SceneError(source_ + ": " + key + ": expected a table ([" + key + "])");
  return TomlSection(node != nullptr ? node->as_table() : nullptr, key, source_);
}

std::vector<TomlSection> TomlDocument::array_of_tables(const std::string& key) const {
  std::vector<TomlSection> tables;
  const toml::node* node = tree_->root.get(key);
  if (node == nullptr) return tables;
  const toml::array* array = node->as_array();
  if (array == nullptr) throw SceneError(source_ + ": " + key + ": expected an array of tables ([[" + key + "]])");
  for (std::size_t i = 0; i < array->size(); ++i) {
    const std::string path = key + "[" + std::to_string(i) + "]";
    const toml::table* table = array->get(i)->as_table();
    if (table == nullptr) throw SceneError(source_ + ": " + path + ": expected a table ([[" + key + "]])");
    tables.emplace_back(table, path, source_);
  }
  return tables;
}

std::string read_scene_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path + ": cannot open the scene file");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace spread::scene
