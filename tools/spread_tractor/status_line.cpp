#include "tools/spread_tractor/status_line.hpp"

#include <cstdio>

#include "libspread/control/fault_codes.hpp"

namespace spread::tractor {

std::string format_fault_codes(std::int32_t fault_codes) {
  if (fault_codes == 0) return "none";
  std::string out;
  const auto bits = static_cast<std::uint32_t>(fault_codes);
  for (std::size_t i = 0; i < firmware::kFaultCount; ++i) {
    if (((bits >> i) & 1u) == 0) continue;
    if (!out.empty()) out += ',';
    out += firmware::fault_name(static_cast<firmware::Fault>(i));
  }
  return out;
}

std::string format_status(const spread::status_t& s) {
  std::string sections;
  for (const bool on : s.section_on) sections += on ? '1' : '0';
  std::string actual;
  for (const bool on : s.section_actual_on) actual += on ? '1' : '0';
  char discs[160];
  std::snprintf(discs, sizeof(discs), "discs=%.1f/%.1f rpm turn=%.1f/%.1f deg flow=%.2f/%.2f%s",
                s.disc_rpm_actual[0], s.disc_rpm_actual[1], s.disc_drop_point_turn_rad[0] * 57.29577951308232,
                s.disc_drop_point_turn_rad[1] * 57.29577951308232, s.disc_flow_fraction[0], s.disc_flow_fraction[1],
                s.sides_pending != 0 ? " (planning)" : "");
  static constexpr const char* kBorders[] = {"off", "left", "right", "field-left", "field-right"};
  const char* border = s.border_mode >= 0 && s.border_mode <= 4 ? kBorders[s.border_mode] : "?";
  std::string modes = std::string(" border=") + border + (s.border_mode != 0 && s.border_applied ? " (applied)" : "") +
                      (s.wind_compensated ? " wind-compensated" : "");
  char line[768];
  std::snprintf(line, sizeof(line),
                "status #%lld seq=%lld %s material='%s' rpm=%.1f->%.1f rate=%.1f/%.1f kg/ha W=%.2f/%.2f m "
                "v=%.2f m/s Q=%.3f kg/s throw=%.2f m eff=%.2f±%.2f m CV=%.1f±%.1f %% %s sections=%s actual=%s %s "
                "rejected(undecodable=%lld fingerprint=%lld invalid=%lld stale=%lld can_malformed=%lld "
                "can_pd=%lld) faults=%s",
                static_cast<long long>(s.step), static_cast<long long>(s.last_command_sequence),
                s.mode == 1 ? "auto" : "manual", s.material.c_str(), s.rpm_actual, s.rpm_target,
                s.rate_actual_kg_ha, s.rate_setpoint_kg_ha, s.width_actual_m, s.width_setpoint_m, s.ground_speed_m_s,
                s.mass_flow_kg_s, s.throw_width_m, s.effective_width_m, 1.96 * s.effective_width_se_m, s.cv_percent,
                1.96 * s.cv_se_percent,
                s.width_reachable ? "reachable" : "OUT-OF-REACH", sections.c_str(), actual.c_str(), (discs + modes).c_str(),
                static_cast<long long>(s.rejected_undecodable), static_cast<long long>(s.rejected_wrong_fingerprint),
                static_cast<long long>(s.rejected_invalid), static_cast<long long>(s.rejected_stale),
                static_cast<long long>(s.can_malformed_frames), static_cast<long long>(s.can_rejected_process_data),
                format_fault_codes(s.fault_codes).c_str());
  return line;
}

std::string format_heartbeat(const spread::heartbeat_t& h) {
  char line[256];
  std::snprintf(line, sizeof(line), "heartbeat #%lld from '%s' loop %.1f Hz ticks=%lld overruns=%lld faults=%s",
                static_cast<long long>(h.sequence), h.node.c_str(), h.loop_rate_mhz / 1000.0,
                static_cast<long long>(h.loop_ticks), static_cast<long long>(h.loop_overruns),
                format_fault_codes(h.fault_codes).c_str());
  return line;
}

}  // namespace spread::tractor
