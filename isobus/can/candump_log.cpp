#include "isobus/can/candump_log.hpp"

#include <charconv>
#include <cstdio>
#include <fstream>
#include <istream>
#include <ostream>
#include <stdexcept>

namespace spread::isobus::can {
namespace {

bool parse_hex(std::string_view text, std::uint32_t& value) {
  if (text.empty()) return false;
  const auto* end = text.data() + text.size();
  const auto result = std::from_chars(text.data(), end, value, 16);
  return result.ec == std::errc{} && result.ptr == end;
}

bool parse_decimal(std::string_view text, std::uint64_t& value) {
  if (text.empty()) return false;
  const auto* end = text.data() + text.size();
  const auto result = std::from_chars(text.data(), end, value, 10);
  return result.ec == std::errc{} && result.ptr == end;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r' || s.back() == '\n')) {
    s.remove_suffix(1);
  }
  return s;
}

}  // namespace

std::optional<CandumpRecord> parse_candump_line(std::string_view line, std::string& error) {
  error.clear();
  line = trim(line);
  if (line.empty() || line.front() == '#') return std::nullopt;
  if (line.front() != '(') {
    error = "expected '(seconds.microseconds)' at the start";
    return std::nullopt;
  }
  const auto close = line.find(')');
  const auto dot = line.find('.');
  if (close == std::string_view::npos || dot == std::string_view::npos || dot > close) {
    error = "timestamp is not '(seconds.microseconds)'";
    return std::nullopt;
  }
  std::uint64_t seconds = 0;
  std::uint64_t micros = 0;
  const std::string_view fraction = line.substr(dot + 1, close - dot - 1);
  if (!parse_decimal(line.substr(1, dot - 1), seconds) || !parse_decimal(fraction, micros) ||
      fraction.size() != 6) {
    error = "timestamp is not '(seconds.microseconds)' with 6 fraction digits";
    return std::nullopt;
  }
  // Range check before converting: the record's time is a signed 64-bit count of nanoseconds.
  if (seconds > kMaxCandumpSeconds) {
    error = "timestamp " + std::string(line.substr(0, close + 1)) + " is beyond the representable range (seconds <= " +
            std::to_string(kMaxCandumpSeconds) + ")";
    return std::nullopt;
  }
  std::string_view rest = trim(line.substr(close + 1));
  const auto space = rest.find_first_of(" \t");
  if (space == std::string_view::npos) {
    error = "missing interface or frame";
    return std::nullopt;
  }
  CandumpRecord record;
  record.interface = std::string(rest.substr(0, space));
  const std::string_view frame_text = trim(rest.substr(space + 1));
  const auto hash = frame_text.find('#');
  if (hash == std::string_view::npos) {
    error = "frame has no '#' between id and data";
    return std::nullopt;
  }
  const std::string_view id_text = frame_text.substr(0, hash);
  std::string_view data_text = frame_text.substr(hash + 1);
  std::uint32_t id = 0;
  if (!parse_hex(id_text, id)) {
    error = "frame id '" + std::string(id_text) + "' is not hexadecimal";
    return std::nullopt;
  }
  if (id_text.size() == 8) {
    if (id > CAN_EFF_MASK) {
      error = "extended id exceeds 29 bits";
      return std::nullopt;
    }
    record.frame.can_id = id | CAN_EFF_FLAG;
  } else if (id_text.size() == 3) {
    if (id > CAN_SFF_MASK) {
      error = "standard id exceeds 11 bits";
      return std::nullopt;
    }
    record.frame.can_id = id;
  } else {
    error = "frame id must have 3 (standard) or 8 (extended) hex digits";
    return std::nullopt;
  }
  if (!data_text.empty() && data_text.front() == '#') {
    error = "CAN FD frames ('##') are not supported";
    return std::nullopt;
  }
  if (!data_text.empty() && (data_text.front() == 'R' || data_text.front() == 'r')) {
    // can-utils writes a remote frame as `ID#R`, optionally followed by its DLC as one digit (`ID#R8`).
    record.frame.can_id |= CAN_RTR_FLAG;
    record.frame.len = 0;
    const std::string_view dlc = data_text.substr(1);
    if (dlc.size() == 1 && dlc[0] >= '0' && dlc[0] <= '8') {
      record.frame.len = static_cast<std::uint8_t>(dlc[0] - '0');
    } else if (!dlc.empty()) {
      error = "remote frame length '" + std::string(dlc) + "' is not one digit 0..8";
      return std::nullopt;
    }
  } else {
    if (data_text.size() % 2 != 0 || data_text.size() > 2 * CAN_MAX_DLEN) {
      error = "data must be 0..8 bytes as pairs of hex digits";
      return std::nullopt;
    }
    record.frame.len = static_cast<std::uint8_t>(data_text.size() / 2);
    for (std::size_t i = 0; i < record.frame.len; ++i) {
      std::uint32_t byte = 0;
      if (!parse_hex(data_text.substr(2 * i, 2), byte)) {
        error = "data byte " + std::to_string(i) + " is not hexadecimal";
        return std::nullopt;
      }
      record.frame.data[i] = static_cast<std::uint8_t>(byte);
    }
  }
  record.time = std::chrono::seconds(seconds) + std::chrono::microseconds(micros);
  return record;
}

std::string format_candump_line(Nanoseconds time, std::string_view interface, const can_frame& frame) {
  const auto micros_total = std::chrono::duration_cast<std::chrono::microseconds>(time).count();
  char head[48];
  std::snprintf(head, sizeof(head), "(%010lld.%06lld) ", static_cast<long long>(micros_total / 1000000),
                static_cast<long long>(micros_total % 1000000));
  std::string out(head);
  out += interface;
  out += ' ';
  char id[16];
  if ((frame.can_id & CAN_EFF_FLAG) != 0) {
    std::snprintf(id, sizeof(id), "%08X#", static_cast<unsigned>(frame.can_id & CAN_EFF_MASK));
  } else {
    std::snprintf(id, sizeof(id), "%03X#", static_cast<unsigned>(frame.can_id & CAN_SFF_MASK));
  }
  out += id;
  if ((frame.can_id & CAN_RTR_FLAG) != 0) {
    out += 'R';
    if (frame.len > 0 && frame.len <= CAN_MAX_DLEN) out += static_cast<char>('0' + frame.len);
  } else {
    const std::size_t n = frame.len > CAN_MAX_DLEN ? CAN_MAX_DLEN : frame.len;
    for (std::size_t i = 0; i < n; ++i) {
      char byte[3];
      std::snprintf(byte, sizeof(byte), "%02X", frame.data[i]);
      out += byte;
    }
  }
  return out;
}

CandumpLog read_candump_log(std::istream& in) {
  CandumpLog log;
  std::string line;
  std::string error;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    auto record = parse_candump_line(line, error);
    if (record) {
      record->line = number;
      log.records.push_back(std::move(*record));
    } else if (!error.empty()) {
      log.errors.push_back("line " + std::to_string(number) + ": " + error);
    }
  }
  return log;
}

CandumpLog read_candump_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("candump log '" + path + "' cannot be opened");
  return read_candump_log(in);
}

CandumpWriter::CandumpWriter(std::ostream& out, const Clock& clock, std::string interface, Nanoseconds epoch_offset)
    : out_(out), clock_(clock), interface_(std::move(interface)), epoch_offset_(epoch_offset) {}

bool CandumpWriter::send(const can_frame& frame) {
  out_ << format_candump_line(clock_.now() + epoch_offset_, interface_, frame) << '\n';
  ++lines_;
  return static_cast<bool>(out_);
}

}  // namespace spread::isobus::can
