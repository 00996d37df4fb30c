#include "libspread/io/tables/blend_rows.hpp"

#include <algorithm>
#include <map>

#include "libspread/io/tables/row_checksum.hpp"
#include "libspread/io/tables/table_rows.hpp"

namespace spread::tables::detail {

std::string blend_component_checksum(const std::string& blend, std::int64_t position, const BlendRowComponent& c) {
  Crc64 crc;
  crc.text(blend);
  crc.integer(position);
  crc.text(c.material);
  crc.real(c.mass_fraction);
  for (double pct : {c.n_pct, c.p2o5_pct, c.k2o_pct}) crc.real(pct);
  return crc.hex();
}

namespace {
bool has_table(Connection& db, const char* table) {
  Statement query(db, "SELECT 1 FROM sqlite_master WHERE type = 'table' AND name = ?");
  query.bind(1, std::string(table));
  return query.step();
}
}  // namespace

std::vector<Blend> read_blend_rows(Connection& db, const std::vector<Material>& materials) {
  std::vector<Blend> blends;
  if (!has_table(db, kBlendComponentsTable)) return blends;
  Statement query(db, "SELECT blend, position, material, mass_fraction, n_pct, p2o5_pct, k2o_pct, checksum "
                      "FROM blend_components ORDER BY blend, position");
  while (query.step()) {
    const std::string blend = query.column_text(0);
    const std::int64_t position = query.column_int(1);
    const std::string row = "blend " + blend + " component " + std::to_string(position);
    BlendRowComponent c;
    c.material = query.column_text(2);
    c.mass_fraction = required_double(query, 3, db, row + " mass_fraction");
    c.n_pct = required_double(query, 4, db, row + " n_pct");
    c.p2o5_pct = required_double(query, 5, db, row + " p2o5_pct");
    c.k2o_pct = required_double(query, 6, db, row + " k2o_pct");
    if (blends.empty() || blends.back().name != blend) blends.push_back(Blend{blend, {}});
    if (position != static_cast<std::int64_t>(blends.back().components.size()))
      raise(TableErrorKind::kCorrupt, db.path(), row + ": positions must run 0, 1, ... (a component row missing?)");
    const bool known = std::any_of(materials.begin(), materials.end(), [&](const Material& m) { return m.name == c.material; });
    if (!known) raise(TableErrorKind::kCorrupt, db.path(), row + ": material \"" + c.material + "\" is not in `materials`");
    // The values first (the message names the field), then the checksum.
    const std::string problem = blend_component_problem(as_blend_component(c));
    if (!problem.empty()) raise(TableErrorKind::kCorrupt, db.path(), row + ": impossible value: " + problem);
    verify_checksum(db, row, query.column_text(7), blend_component_checksum(blend, position, c));
    blends.back().components.push_back(std::move(c));
  }
  for (const Blend& blend : blends) {
    const std::string problem = stored_blend_problem(blend);
    if (!problem.empty()) raise(TableErrorKind::kCorrupt, db.path(), "impossible blend value: " + problem);
  }
  return blends;
}

void write_blend_rows(Connection& db, const Blend& blend) {
  Statement erase(db, "DELETE FROM blend_components WHERE blend = ?");
  erase.bind(1, blend.name);
  erase.step();
  Statement insert(db, "INSERT INTO blend_components (blend, position, material, mass_fraction, n_pct, p2o5_pct, "
                       "k2o_pct, checksum) VALUES (?, ?, ?, ?, ?, ?, ?, ?)");
  for (std::size_t k = 0; k < blend.components.size(); ++k) {
    const BlendRowComponent& c = blend.components[k];
    const auto position = static_cast<std::int64_t>(k);
    insert.reset();
    insert.bind(1, blend.name);
    insert.bind(2, position);
    insert.bind(3, c.material);
    insert.bind(4, c.mass_fraction);
    insert.bind(5, c.n_pct);
    insert.bind(6, c.p2o5_pct);
    insert.bind(7, c.k2o_pct);
    insert.bind(8, blend_component_checksum(blend.name, position, c));
    insert.step();
  }
}

}  // namespace spread::tables::detail
