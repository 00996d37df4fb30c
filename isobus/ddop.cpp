#include "isobus/ddop.hpp"

#include <bit>
#include <cstring>
#include <map>
#include <set>
#include <stdexcept>
#include <string_view>

namespace spread::isobus {
namespace {

class Writer {
 public:
  void tag(const char (&t)[4]) { out_.insert(out_.end(), t, t + 3); }
  void u8(std::uint8_t v) { out_.push_back(v); }
  void u16(std::uint16_t v) {
    out_.push_back(static_cast<std::uint8_t>(v & 0xFFu));
    out_.push_back(static_cast<std::uint8_t>(v >> 8));
  }
  void u32(std::uint32_t v) {
    for (int i = 0; i < 4; ++i) out_.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  void u64(std::uint64_t v) {
    for (int i = 0; i < 8; ++i) out_.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  void text(const std::string& s, const char* field) {
    if (s.size() > 255) throw std::invalid_argument(std::string("DDOP ") + field + " is longer than 255 bytes");
    u8(static_cast<std::uint8_t>(s.size()));
    out_.insert(out_.end(), s.begin(), s.end());
  }
  template <std::size_t N>
  void bytes(const std::array<std::uint8_t, N>& b) {
    out_.insert(out_.end(), b.begin(), b.end());
  }
  void raw(const std::vector<std::uint8_t>& b) { out_.insert(out_.end(), b.begin(), b.end()); }
  std::vector<std::uint8_t> take() { return std::move(out_); }

 private:
  std::vector<std::uint8_t> out_;
};

class Reader {
 public:
  explicit Reader(std::span<const std::uint8_t> b) : b_(b) {}
  std::size_t offset() const { return pos_; }
  bool done() const { return pos_ >= b_.size(); }
  bool u8(std::uint8_t& v) {
    if (b_.size() - pos_ < 1) return false;
    v = b_[pos_++];
    return true;
  }
  bool u16(std::uint16_t& v) {
    if (b_.size() - pos_ < 2) return false;
    v = static_cast<std::uint16_t>(b_[pos_] | (b_[pos_ + 1] << 8));
    pos_ += 2;
    return true;
  }
  bool u32(std::uint32_t& v) {
    if (b_.size() - pos_ < 4) return false;
    v = 0;
    for (int i = 0; i < 4; ++i) v |= std::uint32_t{b_[pos_ + static_cast<std::size_t>(i)]} << (8 * i);
    pos_ += 4;
    return true;
  }
  bool u64(std::uint64_t& v) {
    if (b_.size() - pos_ < 8) return false;
    v = 0;
    for (int i = 0; i < 8; ++i) v |= std::uint64_t{b_[pos_ + static_cast<std::size_t>(i)]} << (8 * i);
    pos_ += 8;
    return true;
  }
  bool text(std::string& s) {
    std::uint8_t n = 0;
    if (!u8(n) || b_.size() - pos_ < n) return false;
    s.assign(reinterpret_cast<const char*>(b_.data() + pos_), n);
    pos_ += n;
    return true;
  }
  template <std::size_t N>
  bool bytes(std::array<std::uint8_t, N>& a) {
    if (b_.size() - pos_ < N) return false;
    std::memcpy(a.data(), b_.data() + pos_, N);
    pos_ += N;
    return true;
  }
  bool raw(std::vector<std::uint8_t>& v, std::size_t n) {
    if (b_.size() - pos_ < n) return false;
    v.assign(b_.begin() + static_cast<std::ptrdiff_t>(pos_), b_.begin() + static_cast<std::ptrdiff_t>(pos_ + n));
    pos_ += n;
    return true;
  }

 private:
  std::span<const std::uint8_t> b_;
  std::size_t pos_ = 0;
};

std::string at(std::size_t offset) { return " (byte " + std::to_string(offset) + ")"; }

}  // namespace

std::uint16_t object_id(const DdopObject& object) {
  return std::visit([](const auto& o) { return o.id; }, object);
}

std::string label_hex(const std::array<std::uint8_t, 7>& label) {
  static constexpr char kDigits[] = "0123456789ABCDEF";
  std::string s;
  for (const std::uint8_t b : label) {
    s += kDigits[b >> 4];
    s += kDigits[b & 0x0F];
  }
  return s;
}

std::vector<std::uint8_t> write_ddop(const Ddop& pool, std::uint8_t version) {
  Writer w;
  for (const DdopObject& object : pool.objects) {
    if (const auto* d = std::get_if<DeviceObject>(&object)) {
      w.tag("DVC");
      w.u16(d->id);
      w.text(d->designator, "device designator");
      w.text(d->software_version, "software version");
      w.u64(d->working_set_master_name);
      w.text(d->serial_number, "serial number");
      w.bytes(d->structure_label);
      w.bytes(d->localization_label);
      if (version >= 4) {
        // ISO 11783-10 Annex B, device object of version 4: a length byte and the extended structure
        // label after the localisation label.
        if (d->extended_structure_label.size() > kMaxExtendedStructureLabel) {
          throw std::invalid_argument("DDOP extended structure label is longer than 32 bytes");
        }
        w.u8(static_cast<std::uint8_t>(d->extended_structure_label.size()));
        w.raw(d->extended_structure_label);
      }
    } else if (const auto* e = std::get_if<DeviceElement>(&object)) {
      if (e->children.size() > 0xFFFF) throw std::invalid_argument("DDOP element has more than 65535 children");
      w.tag("DET");
      w.u16(e->id);
      w.u8(static_cast<std::uint8_t>(e->type));
      w.text(e->designator, "element designator");
      w.u16(e->element_number);
      w.u16(e->parent_id);
      w.u16(static_cast<std::uint16_t>(e->children.size()));
      for (const std::uint16_t child : e->children) w.u16(child);
    } else if (const auto* p = std::get_if<DeviceProcessData>(&object)) {
      w.tag("DPD");
      w.u16(p->id);
      w.u16(p->ddi);
      w.u8(p->properties);
      w.u8(p->triggers);
      w.text(p->designator, "process data designator");
      w.u16(p->presentation_id);
    } else if (const auto* t = std::get_if<DeviceProperty>(&object)) {
      w.tag("DPT");
      w.u16(t->id);
      w.u16(t->ddi);
      w.u32(static_cast<std::uint32_t>(t->value));
      w.text(t->designator, "property designator");
      w.u16(t->presentation_id);
    } else if (const auto* v = std::get_if<DeviceValuePresentation>(&object)) {
      w.tag("DVP");
      w.u16(v->id);
      w.u32(static_cast<std::uint32_t>(v->offset));
      w.u32(std::bit_cast<std::uint32_t>(v->scale));
      w.u8(v->decimals);
      w.text(v->unit, "unit designator");
    }
  }
  return w.take();
}

DdopParseResult parse_ddop(std::span<const std::uint8_t> bytes, std::uint8_t version) {
  DdopParseResult result;
  Ddop pool;
  Reader r(bytes);
  auto fail = [&](const std::string& what, std::size_t offset) {
    result.error = what + at(offset);
    return result;
  };
  std::map<std::uint16_t, std::size_t> index;  // object ID -> position in pool.objects
  while (!r.done()) {
    const std::size_t start = r.offset();
    std::array<std::uint8_t, 3> tag{};
    if (!r.bytes(tag)) return fail("truncated object type", start);
    const std::string_view t(reinterpret_cast<const char*>(tag.data()), 3);
    bool ok = false;
    if (t == "DVC") {
      DeviceObject d;
      ok = r.u16(d.id) && r.text(d.designator) && r.text(d.software_version) && r.u64(d.working_set_master_name) &&
           r.text(d.serial_number) && r.bytes(d.structure_label) && r.bytes(d.localization_label);
      if (ok && version >= 4) {
        std::uint8_t n = 0;
        ok = r.u8(n);
        if (ok && n > kMaxExtendedStructureLabel) {
          return fail("extended structure label of " + std::to_string(n) + " bytes (at most 32)", start);
        }
        ok = ok && r.raw(d.extended_structure_label, n);
      }
      if (ok) pool.objects.emplace_back(std::move(d));
    } else if (t == "DET") {
      DeviceElement e;
      std::uint8_t type = 0;
      std::uint16_t count = 0;
      ok = r.u16(e.id) && r.u8(type) && r.text(e.designator) && r.u16(e.element_number) && r.u16(e.parent_id) &&
           r.u16(count);
      if (ok && (type < 1 || type > 7)) return fail("device element type " + std::to_string(type) + " unknown", start);
      e.type = static_cast<ElementType>(type);
      for (std::uint16_t i = 0; ok && i < count; ++i) {
        std::uint16_t child = 0;
        ok = r.u16(child);
        e.children.push_back(child);
      }
      if (ok) pool.objects.emplace_back(std::move(e));
    } else if (t == "DPD") {
      DeviceProcessData p;
      ok = r.u16(p.id) && r.u16(p.ddi) && r.u8(p.properties) && r.u8(p.triggers) && r.text(p.designator) &&
           r.u16(p.presentation_id);
      if (ok) pool.objects.emplace_back(std::move(p));
    } else if (t == "DPT") {
      DeviceProperty p;
      std::uint32_t value = 0;
      ok = r.u16(p.id) && r.u16(p.ddi) && r.u32(value) && r.text(p.designator) && r.u16(p.presentation_id);
      p.value = static_cast<std::int32_t>(value);
      if (ok) pool.objects.emplace_back(std::move(p));
    } else if (t == "DVP") {
      DeviceValuePresentation v;
      std::uint32_t offset = 0;
      std::uint32_t scale = 0;
      ok = r.u16(v.id) && r.u32(offset) && r.u32(scale) && r.u8(v.decimals) && r.text(v.unit);
      v.offset = static_cast<std::int32_t>(offset);
      v.scale = std::bit_cast<float>(scale);
      if (ok) pool.objects.emplace_back(std::move(v));
    } else {
      return fail("unknown object type '" + std::string(t) + "'", start);
    }
    if (!ok) return fail("object " + std::string(t) + " is truncated", start);
    const std::uint16_t id = object_id(pool.objects.back());
    if (id == kNullObjectId) return fail("object ID 65535 is reserved", start);
    if (!index.emplace(id, pool.objects.size() - 1).second) {
      return fail("object ID " + std::to_string(id) + " used twice", start);
    }
  }

  // References: what a task controller follows when it builds its picture of the implement.
  auto find = [&](std::uint16_t id) -> const DdopObject* {
    const auto it = index.find(id);
    return it == index.end() ? nullptr : &pool.objects[it->second];
  };
  int devices = 0;
  int device_elements = 0;
  std::set<std::uint16_t> element_numbers;
  for (const DdopObject& object : pool.objects) {
    if (std::holds_alternative<DeviceObject>(object)) ++devices;
    auto presentation_ok = [&](std::uint16_t id) {
      return id == kNullObjectId || (find(id) != nullptr && std::holds_alternative<DeviceValuePresentation>(*find(id)));
    };
    if (const auto* p = std::get_if<DeviceProcessData>(&object); p && !presentation_ok(p->presentation_id)) {
      result.error = "process data " + std::to_string(p->id) + " refers to presentation " +
                     std::to_string(p->presentation_id) + ", which is not a DVP";
      return result;
    }
    if (const auto* p = std::get_if<DeviceProperty>(&object); p && !presentation_ok(p->presentation_id)) {
      result.error = "property " + std::to_string(p->id) + " refers to presentation " +
                     std::to_string(p->presentation_id) + ", which is not a DVP";
      return result;
    }
    const auto* e = std::get_if<DeviceElement>(&object);
    if (e == nullptr) continue;
    if (!element_numbers.insert(e->element_number).second) {
      result.error = "element number " + std::to_string(e->element_number) + " used twice";
      return result;
    }
    if (e->element_number > 0x0FFF) {
      result.error = "element " + std::to_string(e->id) + ": element number " + std::to_string(e->element_number) +
                     " exceeds 12 bits";
      return result;
    }
    const DdopObject* parent = find(e->parent_id);
    if (e->type == ElementType::kDevice) {
      ++device_elements;
      if (parent == nullptr || !std::holds_alternative<DeviceObject>(*parent)) {
        result.error = "device element " + std::to_string(e->id) + " must have the DVC as parent";
        return result;
      }
    } else if (parent == nullptr || !std::holds_alternative<DeviceElement>(*parent)) {
      result.error = "element " + std::to_string(e->id) + " has parent " + std::to_string(e->parent_id) +
                     ", which is not a device element";
      return result;
    }
    // ISO 11783-10 Annex B, device element object: its object references are its DPD and DPT objects;
    // child elements are found through their parent object ID, never listed here.
    for (const std::uint16_t child : e->children) {
      const DdopObject* c = find(child);
      const bool allowed =
          c != nullptr && (std::holds_alternative<DeviceProcessData>(*c) || std::holds_alternative<DeviceProperty>(*c));
      if (!allowed) {
        result.error = "element " + std::to_string(e->id) + " lists child " + std::to_string(child) +
                       ", which is not a DPD or DPT of this pool";
        return result;
      }
    }
    // The parent chain ends at the device element without a cycle.
    std::set<std::uint16_t> seen{e->id};
    const DeviceElement* walk = e;
    while (walk->type != ElementType::kDevice) {
      const auto* up = std::get_if<DeviceElement>(find(walk->parent_id));
      if (up == nullptr || !seen.insert(up->id).second) {
        result.error = "element " + std::to_string(e->id) + " does not lead to the device element";
        return result;
      }
      walk = up;
    }
  }
  if (devices != 1) {
    result.error = "a pool needs exactly one DVC, found " + std::to_string(devices);
    return result;
  }
  if (device_elements != 1) {
    result.error = "a pool needs exactly one device-type DET, found " + std::to_string(device_elements);
    return result;
  }
  result.pool = std::move(pool);
  return result;
}

}  // namespace spread::isobus
