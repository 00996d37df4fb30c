// The spreader's device descriptor object pool read back by a decoder written here from the object layouts
// of ISO 11783-10 Annex B, not through isobus/ddop.cpp: what a task controller built from the
// standard would see. Layouts (little endian; "text" = a length byte and that many bytes):
//   DVC  tag, object ID u16, designator text, software version text, NAME 8 bytes, serial number text,
//        structure label 7 bytes, localisation label 7 bytes, [version 4: extended structure label text]
//   DET  tag, object ID u16, type u8, designator text, element number u16, parent object ID u16,
//        number of object references u16, object IDs u16 each
//   DPD  tag, object ID u16, DDI u16, properties u8, trigger methods u8, designator text, presentation u16
//   DPT  tag, object ID u16, DDI u16, value i32, designator text, presentation u16
//   DVP  tag, object ID u16, offset i32, scale f32, decimals u8, unit text
#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "firmware_sim/can/spreader_ddop.hpp"
#include "isobus/ddop.hpp"

namespace {

struct StdObject {
  std::string tag;
  std::uint16_t id = 0;
  // DET
  std::uint8_t type = 0;
  std::uint16_t element_number = 0;
  std::uint16_t parent = 0;
  std::vector<std::uint16_t> references;
  // DPD / DPT
  std::uint16_t ddi = 0;
  std::uint8_t properties = 0;
  std::int32_t value = 0;
  // DVC
  std::vector<std::uint8_t> structure_label;
  std::vector<std::uint8_t> extended_structure_label;
  bool has_extended_label = false;
};

// Decodes the whole pool or fails the test; `version` as the TC negotiated it.
std::vector<StdObject> decode(const std::vector<std::uint8_t>& b, int version) {
  std::vector<StdObject> out;
  std::size_t i = 0;
  auto need = [&](std::size_t n) {
    if (b.size() - i < n) throw std::runtime_error("pool ends inside an object at byte " + std::to_string(i));
  };
  auto u8 = [&] {
    need(1);
    return b[i++];
  };
  auto u16 = [&] {
    need(2);
    const auto v = static_cast<std::uint16_t>(b[i] | (b[i + 1] << 8));
    i += 2;
    return v;
  };
  auto u32 = [&] {
    need(4);
    std::uint32_t v = 0;
    for (int k = 0; k < 4; ++k) v |= std::uint32_t{b[i + static_cast<std::size_t>(k)]} << (8 * k);
    i += 4;
    return v;
  };
  auto skip = [&](std::size_t n) {
    need(n);
    i += n;
  };
  auto bytes = [&](std::size_t n) {
    need(n);
    std::vector<std::uint8_t> v(b.begin() + static_cast<std::ptrdiff_t>(i),
                                b.begin() + static_cast<std::ptrdiff_t>(i + n));
    i += n;
    return v;
  };
  auto text = [&] { skip(u8()); };
  while (i < b.size()) {
    StdObject o;
    need(3);
    o.tag.assign(b.begin() + static_cast<std::ptrdiff_t>(i), b.begin() + static_cast<std::ptrdiff_t>(i + 3));
    i += 3;
    o.id = u16();
    if (o.tag == "DVC") {
      text();      // designator
      text();      // software version
      skip(8);     // NAME
      text();      // serial number
      o.structure_label = bytes(7);
      skip(7);     // localisation label
      if (version >= 4) {
        o.has_extended_label = true;
        o.extended_structure_label = bytes(u8());
      }
    } else if (o.tag == "DET") {
      o.type = u8();
      text();
      o.element_number = u16();
      o.parent = u16();
      const std::uint16_t n = u16();
      for (std::uint16_t k = 0; k < n; ++k) o.references.push_back(u16());
    } else if (o.tag == "DPD") {
      o.ddi = u16();
      o.properties = u8();
      u8();  // trigger methods
      text();
      u16();  // presentation
    } else if (o.tag == "DPT") {
      o.ddi = u16();
      o.value = static_cast<std::int32_t>(u32());
      text();
      u16();
    } else if (o.tag == "DVP") {
      u32();
      u32();
      u8();
      text();
    } else {
      throw std::runtime_error("unknown table ID '" + o.tag + "' at byte " + std::to_string(i - 5));
    }
    out.push_back(std::move(o));
  }
  return out;
}

std::vector<std::uint8_t> spreader_pool(std::uint8_t version) {
  spread::firmware::can::SpreaderDescription d;
  d.section_count = 8;
  d.working_width_m = 24.0;
  d.boom_offset_x_m = -1.0;
  return spread::isobus::write_ddop(spread::firmware::can::make_spreader_ddop(d), version);
}

TEST(DdopStandardReader, VersionFourPoolHasTheExtendedLabelAndAnElementTreeByParentId) {
  const std::vector<StdObject> objects = decode(spreader_pool(4), 4);
  std::map<std::string, int> count;
  std::map<std::uint16_t, const StdObject*> by_id;
  for (const StdObject& o : objects) {
    ++count[o.tag];
    EXPECT_TRUE(by_id.emplace(o.id, &o).second) << "object ID " << o.id << " twice";
  }
  // 1 device; device, boom, hopper, discs, connector and 8 sections; 13 standard process data and 5
  // proprietary ones (border and wind); 3 boom offsets, 3 connector properties and 3 per section; 5
  // presentations.
  EXPECT_EQ(count["DVC"], 1);
  EXPECT_EQ(count["DET"], 13);
  EXPECT_EQ(count["DPD"], 18);
  EXPECT_EQ(count["DPT"], 30);
  EXPECT_EQ(count["DVP"], 5);
  EXPECT_EQ(objects.size(), 67u);

  // Version 4: the device object carries its extended structure label (length byte 7, then 'LSP' and the
  // boom's X offset, -1000 mm).
  const StdObject& dvc = objects.front();
  ASSERT_EQ(dvc.tag, "DVC");
  ASSERT_TRUE(dvc.has_extended_label);
  EXPECT_EQ(dvc.extended_structure_label,
            (std::vector<std::uint8_t>{'L', 'S', 'P', 0x18, 0xFC, 0xFF, 0xFF}));
  EXPECT_EQ(objects[1].tag, "DET") << "the length byte is exact: the next object starts right after the label";

  const StdObject* device = nullptr;
  const StdObject* boom = nullptr;
  for (const StdObject& o : objects) {
    if (o.tag == "DET" && o.type == 1) device = &o;
    if (o.tag == "DET" && o.element_number == 1) boom = &o;
  }
  ASSERT_NE(device, nullptr);
  ASSERT_NE(boom, nullptr);
  EXPECT_EQ(device->parent, dvc.id);
  EXPECT_EQ(boom->parent, device->id);

  int sections = 0;
  int connectors = 0;
  for (const StdObject& o : objects) {
    if (o.tag != "DET") continue;
    // Every object reference of an element is one of its DPD / DPT objects, never another element.
    for (const std::uint16_t ref : o.references) {
      ASSERT_TRUE(by_id.count(ref)) << "DET " << o.id << " references missing object " << ref;
      const std::string& t = by_id.at(ref)->tag;
      EXPECT_TRUE(t == "DPD" || t == "DPT") << "DET " << o.id << " references a " << t << " (" << ref << ")";
    }
    // Every parent resolves: the DVC for the device element, a DET otherwise.
    ASSERT_TRUE(by_id.count(o.parent)) << "DET " << o.id << " parent " << o.parent;
    EXPECT_EQ(by_id.at(o.parent)->tag, o.type == 1 ? "DVC" : "DET");
    if (o.type == 4) {
      ++sections;
      EXPECT_EQ(o.parent, boom->id) << "sections hang under the boom";
    } else if (o.type == 6) {
      ++connectors;
      EXPECT_EQ(o.parent, device->id);
      std::map<std::uint16_t, std::int32_t> properties;
      for (const std::uint16_t ref : o.references) properties[by_id.at(ref)->ddi] = by_id.at(ref)->value;
      EXPECT_EQ(properties.at(157), 3) << "connector type: three-point hitch, mounted";
      EXPECT_TRUE(properties.count(134) && properties.count(135)) << "connector offsets";
    } else if (o.type != 1) {
      EXPECT_EQ(o.parent, device->id);
    }
  }
  EXPECT_EQ(sections, 8);
  EXPECT_EQ(connectors, 1);

  // DDI 160 (section control state) is a settable process data of the boom.
  bool section_control = false;
  for (const std::uint16_t ref : boom->references) {
    const StdObject& p = *by_id.at(ref);
    if (p.tag == "DPD" && p.ddi == 160) section_control = (p.properties & 0x02) != 0;
  }
  EXPECT_TRUE(section_control);
}

TEST(DdopStandardReader, VersionThreePoolHasNoExtendedLabel) {
  const std::vector<std::uint8_t> v4 = spreader_pool(4);
  const std::vector<std::uint8_t> v3 = spreader_pool(3);
  EXPECT_EQ(v4.size(), v3.size() + 8) << "the length byte and the 7-byte extended label";
  const std::vector<StdObject> objects = decode(v3, 3);
  EXPECT_EQ(objects.size(), 67u);
  EXPECT_FALSE(objects.front().has_extended_label);
  // A version-4 reader of the version-3 bytes takes the next object's tag for a length: it must not come
  // out as the same pool (the two layouts really differ).
  EXPECT_ANY_THROW({
    const auto misread = decode(v3, 4);
    if (misread.size() == 61u) throw std::runtime_error("same");
  });
}

}  // namespace
