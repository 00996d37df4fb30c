#include "tools/spread_tractor/ddop_tree.hpp"

#include <cstdio>
#include <map>
#include <vector>

#include "isobus/frame_description.hpp"
#include "isobus/iso_name.hpp"

namespace spread::tractor {
namespace {

using namespace isobus;

const char* element_type_name(ElementType type) {
  switch (type) {
    case ElementType::kDevice: return "device";
    case ElementType::kFunction: return "function";
    case ElementType::kBin: return "bin";
    case ElementType::kSection: return "section";
    case ElementType::kUnit: return "unit";
    case ElementType::kConnector: return "connector";
    case ElementType::kNavigationReference: return "navigation reference";
  }
  return "element type ?";
}

std::string properties_text(std::uint8_t properties, std::uint8_t triggers) {
  std::string s;
  auto add = [&s](const char* word) {
    if (!s.empty()) s += ", ";
    s += word;
  };
  if (properties & kPropertySettable) add("settable");
  if (properties & kPropertyDefaultSet) add("default set");
  if (properties & kPropertyControlSource) add("control source");
  std::string t;
  auto add_trigger = [&t](const char* word) {
    if (!t.empty()) t += "/";
    t += word;
  };
  if (triggers & kTriggerTimeInterval) add_trigger("time");
  if (triggers & kTriggerDistanceInterval) add_trigger("distance");
  if (triggers & kTriggerThresholdLimits) add_trigger("thresholds");
  if (triggers & kTriggerOnChange) add_trigger("on change");
  if (triggers & kTriggerTotal) add_trigger("total");
  if (!t.empty()) add(("triggers " + t).c_str());
  return s;
}

// Bytes as hex digits, for the version-4 extended structure label (any length up to 32).
std::string hex_bytes(const std::vector<std::uint8_t>& bytes) {
  static constexpr char kDigits[] = "0123456789ABCDEF";
  std::string s;
  for (const std::uint8_t b : bytes) {
    s += kDigits[b >> 4];
    s += kDigits[b & 0x0F];
  }
  return s;
}

class TreeWriter {
 public:
  explicit TreeWriter(const Ddop& pool) {
    for (const DdopObject& o : pool.objects) {
      by_id_[object_id(o)] = &o;
      if (const auto* e = std::get_if<DeviceElement>(&o)) child_elements_[e->parent_id].push_back(e);
    }
  }

  std::string write(const Ddop& pool) {
    for (const DdopObject& o : pool.objects) {
      const auto* d = std::get_if<DeviceObject>(&o);
      if (!d) continue;
      out_ += "DVC " + std::to_string(d->id) + " \"" + d->designator + "\" software " + d->software_version +
              ", serial " + d->serial_number + "\n    " + describe_name(d->working_set_master_name) +
              "\n    structure label " + isobus::label_hex(d->structure_label) + ", localisation label " +
              isobus::label_hex(d->localization_label) +
              (d->extended_structure_label.empty() ? std::string()
                                                   : ", extended structure label " +
                                                         hex_bytes(d->extended_structure_label)) +
              "\n";
      elements_under(d->id, "");
    }
    return out_;
  }

 private:
  void elements_under(std::uint16_t parent, const std::string& indent) {
    const auto it = child_elements_.find(parent);
    if (it == child_elements_.end()) return;
    for (const DeviceElement* e : it->second) {
      if (e->id == parent) continue;  // a self-parented element would never end
      out_ += indent + "└ DET " + std::to_string(e->id) + " " + element_type_name(e->type) + " \"" +
              e->designator + "\" element " + std::to_string(e->element_number) + "\n";
      const std::string inner = indent + "   ";
      for (const std::uint16_t child : e->children) {
        const auto c = by_id_.find(child);
        if (c == by_id_.end()) continue;
        if (const auto* p = std::get_if<DeviceProcessData>(c->second)) {
          out_ += inner + "DPD " + std::to_string(p->id) + " DDI " + std::to_string(p->ddi) + " " +
                  isobus::ddi_name(p->ddi) + " \"" + p->designator + "\" (" +
                  properties_text(p->properties, p->triggers) + ")" + unit_of(p->presentation_id) + "\n";
        } else if (const auto* t = std::get_if<DeviceProperty>(c->second)) {
          out_ += inner + "DPT " + std::to_string(t->id) + " DDI " + std::to_string(t->ddi) + " " +
                  isobus::ddi_name(t->ddi) + " \"" + t->designator + "\" = " +
                  presented(t->value, t->presentation_id) + "\n";
        }
      }
      elements_under(e->id, inner);
    }
  }

  const DeviceValuePresentation* presentation(std::uint16_t id) const {
    if (id == kNullObjectId) return nullptr;
    const auto it = by_id_.find(id);
    return it == by_id_.end() ? nullptr : std::get_if<DeviceValuePresentation>(it->second);
  }
  std::string unit_of(std::uint16_t id) const {
    const auto* v = presentation(id);
    return v ? " [" + v->unit + "]" : "";
  }
  // ISO 11783-10 B.7: shown value = (raw + offset) × scale, with `decimals` digits.
  std::string presented(std::int32_t raw, std::uint16_t id) const {
    const auto* v = presentation(id);
    if (!v) return std::to_string(raw);
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f %s", static_cast<int>(v->decimals > 9 ? 9 : v->decimals),
                  (static_cast<double>(raw) + v->offset) * static_cast<double>(v->scale), v->unit.c_str());
    return std::to_string(raw) + " (" + buf + ")";
  }

  std::map<std::uint16_t, const DdopObject*> by_id_;
  std::map<std::uint16_t, std::vector<const DeviceElement*>> child_elements_;
  std::string out_;
};

}  // namespace

std::string describe_ddop_tree(const Ddop& pool) { return TreeWriter(pool).write(pool); }

}  // namespace spread::tractor
