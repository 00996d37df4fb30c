#include "tools/spread_tractor/as_applied_csv.hpp"

#include <cstdio>

#include "isobus/frame_description.hpp"

namespace spread::tractor {

void write_as_applied_header(std::ostream& out) { out << "time_s,source,element,ddi,ddi_name,value_raw,value\n"; }

void write_as_applied_line(std::ostream& out, const isobus::AsAppliedRecord& r, double time_s) {
  char head[64];
  std::snprintf(head, sizeof head, "%.3f,0x%02X,%u,%u,", time_s, r.source, unsigned{r.element}, unsigned{r.ddi});
  // Neither the names nor the formatted values contain commas; quoted anyway so that a spreadsheet
  // keeps "250.00 kg/ha" in one cell whatever a later DDI name holds.
  out << head << '"' << isobus::ddi_name(r.ddi) << "\"," << r.value << ",\""
      << isobus::format_ddi_value(r.ddi, r.value) << "\"\n";
}

}  // namespace spread::tractor
