#pragma once
// One row per column of the `machine` table, in the table's column order, which is also the order of the
// row checksum's values (docs/table-format.md). The name is the column, the `Machine` member and the docs'
// row. The writer's INSERT, the reader's SELECT, the checksum and lookup_builder's comparison of a file's
// machine with a scene's all walk these rows, so a column is added here once; tests/tables/test_machine_schema.cpp
// checks the CREATE statement and the docs' tables against them, and the static_asserts below fail the
// build when `Machine` gains a member without a row (tests/tables/test_format_version.cpp then asks for
// the format version's bump).
#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <utility>

#include "libspread/io/tables/table_format.hpp"

namespace spread::tables {

struct MachineColumn {
  enum class Kind { kText, kReal, kInteger };
  std::string_view name;
  Kind kind;
  std::string Machine::* text = nullptr;
  double Machine::* real = nullptr;
  int Machine::* integer = nullptr;
  std::string_view sql_type() const {
    switch (kind) {
      case Kind::kText: return "TEXT";
      case Kind::kReal: return "REAL";
      case Kind::kInteger: return "INTEGER";
    }
    return "";
  }
};

inline constexpr std::array<MachineColumn, 8> kMachineColumns{{
    {"name", MachineColumn::Kind::kText, &Machine::name},
    {"disc_radius_m", MachineColumn::Kind::kReal, nullptr, &Machine::disc_radius_m},
    {"disc_height_m", MachineColumn::Kind::kReal, nullptr, &Machine::disc_height_m},
    {"disc_spacing_m", MachineColumn::Kind::kReal, nullptr, &Machine::disc_spacing_m},
    {"disc_count", MachineColumn::Kind::kInteger, nullptr, nullptr, &Machine::disc_count},
    {"vane_count", MachineColumn::Kind::kInteger, nullptr, nullptr, &Machine::vane_count},
    {"cone_angle_rad", MachineColumn::Kind::kReal, nullptr, &Machine::cone_angle_rad},
    {"rotation_sense", MachineColumn::Kind::kInteger, nullptr, nullptr, &Machine::rotation_sense},
}};

namespace machine_schema_detail {
// The members of an aggregate, counted by the most initialisers it takes (each converts to any member).
struct AnyMember {
  template <class T>
  constexpr operator T&() const&& noexcept;
};
template <class T, std::size_t... I>
constexpr bool initialisable_with(std::index_sequence<I...>) {
  return requires { T{(void(I), AnyMember{})...}; };
}
template <class T, std::size_t N = 0>
constexpr std::size_t member_count() {
  if constexpr (!initialisable_with<T>(std::make_index_sequence<N + 1>{})) {
    return N;
  } else {
    return member_count<T, N + 1>();
  }
}
// Each row names the member its kind needs, and no member or name twice.
constexpr bool columns_are_well_formed() {
  for (std::size_t a = 0; a < kMachineColumns.size(); ++a) {
    const MachineColumn& c = kMachineColumns[a];
    if ((c.kind == MachineColumn::Kind::kText) != (c.text != nullptr)) return false;
    if ((c.kind == MachineColumn::Kind::kReal) != (c.real != nullptr)) return false;
    if ((c.kind == MachineColumn::Kind::kInteger) != (c.integer != nullptr)) return false;
    for (std::size_t b = 0; b < a; ++b) {
      const MachineColumn& d = kMachineColumns[b];
      if ((c.text != nullptr && c.text == d.text) || (c.real != nullptr && c.real == d.real) ||
          (c.integer != nullptr && c.integer == d.integer) || c.name == d.name) {
        return false;
      }
    }
  }
  return true;
}
}  // namespace machine_schema_detail
static_assert(machine_schema_detail::columns_are_well_formed(),
              "kMachineColumns: a row without the member its kind needs, or a member or name listed twice");
static_assert(machine_schema_detail::member_count<Machine>() == kMachineColumns.size(),
              "tables::Machine has a member that kMachineColumns does not list (or lists one it lacks): add its row, "
              "its column to kSchemaSql, its line to docs/table-format.md, and bump kFormatVersion");

}  // namespace spread::tables
