#pragma once
// The as-applied log a task controller keeps (ISO 11783-10 data logging: every value the client reports,
// with its time and element) as CSV, one header line and one line per value:
//   time_s,source,element,ddi,ddi_name,value_raw,value
// time_s counts from the start of the session; value is the raw value in the DDI's display unit.
#include <ostream>
#include <string>

#include "isobus/tc_server.hpp"

namespace spread::tractor {

void write_as_applied_header(std::ostream& out);
void write_as_applied_line(std::ostream& out, const isobus::AsAppliedRecord& record, double time_s);

}  // namespace spread::tractor
