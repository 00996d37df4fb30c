// The spreader's device descriptor object pool (ISO 11783-10 Annex B): byte layout, structure, and a
// reader that refuses every malformed pool with the reason and never reads past the bytes.
#include <gtest/gtest.h>

#include <map>
#include <set>

#include "firmware_sim/can/spreader_ddop.hpp"
#include "isobus/ddi.hpp"
#include "isobus/ddop.hpp"

namespace spread::firmware::can {
namespace {

using namespace isobus;

std::vector<std::uint8_t> spreader_bytes(int sections = 8) {
  SpreaderDescription d;
  d.section_count = sections;
  d.name = 0xA00A8000001234ull;
  return write_ddop(make_spreader_ddop(d));
}

template <typename T>
std::vector<T> all_of(const Ddop& pool) {
  std::vector<T> out;
  for (const auto& o : pool.objects) {
    if (const auto* t = std::get_if<T>(&o)) out.push_back(*t);
  }
  return out;
}

TEST(Ddop, ObjectBytesFollowAnnexB) {
  Ddop pool;
  DeviceObject dvc;
  dvc.id = 0;
  dvc.designator = "S";
  dvc.software_version = "1";
  dvc.working_set_master_name = 0x0102030405060708ull;
  dvc.serial_number = "9";
  dvc.structure_label = {1, 2, 3, 4, 5, 6, 7};
  dvc.localization_label = {'e', 'n', 0x50, 0, 0, 0, 0xFF};
  dvc.extended_structure_label = {0xAB, 0xCD};
  pool.objects.emplace_back(dvc);
  pool.objects.emplace_back(DeviceElement{1, ElementType::kDevice, "D", 0, 0, {2, 3}});
  pool.objects.emplace_back(DeviceProcessData{2, 141, 0x01, 0x0F, "W", 0xFFFF});
  pool.objects.emplace_back(DeviceProperty{3, 134, -1000, "X", 4});
  pool.objects.emplace_back(DeviceValuePresentation{4, 0, 0.001f, 2, "m"});
  const std::vector<std::uint8_t> expected = {
      'D', 'V', 'C', 0x00, 0x00, 1, 'S', 1, '1', 0x08, 0x07, 0x06, 0x05, 0x04, 0x03, 0x02, 0x01, 1, '9',
      1, 2, 3, 4, 5, 6, 7, 'e', 'n', 0x50, 0, 0, 0, 0xFF, 2, 0xAB, 0xCD,  // version 4: extended label
      'D', 'E', 'T', 0x01, 0x00, 1, 1, 'D', 0x00, 0x00, 0x00, 0x00, 0x02, 0x00, 0x02, 0x00, 0x03, 0x00,
      'D', 'P', 'D', 0x02, 0x00, 0x8D, 0x00, 0x01, 0x0F, 1, 'W', 0xFF, 0xFF,
      'D', 'P', 'T', 0x03, 0x00, 0x86, 0x00, 0x18, 0xFC, 0xFF, 0xFF, 1, 'X', 0x04, 0x00,
      'D', 'V', 'P', 0x04, 0x00, 0, 0, 0, 0, 0x6F, 0x12, 0x83, 0x3A, 2, 1, 'm'};  // 0.001f = 0x3A83126F
  EXPECT_EQ(write_ddop(pool), expected);
  const DdopParseResult back = parse_ddop(expected);
  ASSERT_TRUE(back.pool.has_value()) << back.error;
  EXPECT_EQ(write_ddop(*back.pool), expected);

  // Version 3 has no extended structure label: the same pool is 3 bytes shorter and reads back at 3.
  std::vector<std::uint8_t> v3 = expected;
  v3.erase(v3.begin() + 33, v3.begin() + 36);
  EXPECT_EQ(write_ddop(pool, 3), v3);
  const DdopParseResult back3 = parse_ddop(v3, 3);
  ASSERT_TRUE(back3.pool.has_value()) << back3.error;
  EXPECT_TRUE(std::get<DeviceObject>(back3.pool->objects[0]).extended_structure_label.empty());
  EXPECT_FALSE(parse_ddop(v3, 4).pool.has_value()) << "a version-3 pool is not a valid version-4 pool";

  dvc.extended_structure_label.assign(33, 0);
  pool.objects[0] = dvc;
  EXPECT_THROW(write_ddop(pool), std::invalid_argument) << "at most 32 bytes";
}

TEST(Ddop, SpreaderPoolDescribesDeviceBoomBinDiscAndEachSection) {
  const std::vector<std::uint8_t> bytes = spreader_bytes(8);
  const DdopParseResult parsed = parse_ddop(bytes);
  ASSERT_TRUE(parsed.pool.has_value()) << parsed.error;
  EXPECT_EQ(write_ddop(*parsed.pool), bytes) << "reader and writer are inverse";
  const Ddop& pool = *parsed.pool;

  const auto dvc = all_of<DeviceObject>(pool);
  ASSERT_EQ(dvc.size(), 1u);
  EXPECT_EQ(dvc[0].working_set_master_name, 0xA00A8000001234ull);
  std::map<std::uint16_t, DeviceElement> elements;  // by object ID
  for (const auto& e : all_of<DeviceElement>(pool)) elements[e.id] = e;
  std::map<std::uint16_t, std::uint16_t> parent_element;  // child object ID -> element number
  for (const auto& [id, e] : elements) {
    for (const std::uint16_t child : e.children) parent_element[child] = e.element_number;
  }

  // Each section: an element of type section under the boom, with X/Y offsets and its width (DPT 67).
  int sections = 0;
  std::set<std::int32_t> y_offsets_mm;
  for (const auto& [id, e] : elements) {
    if (e.type != ElementType::kSection) continue;
    ++sections;
    EXPECT_EQ(elements.at(e.parent_id).designator, "Boom");
    std::map<std::uint16_t, std::int32_t> values;
    for (const auto& p : all_of<DeviceProperty>(pool)) {
      if (parent_element.at(p.id) == e.element_number) values[p.ddi] = p.value;
    }
    EXPECT_EQ(values.at(67), 3000) << "24 m over 8 sections";
    EXPECT_EQ(values.at(134), -1000);
    y_offsets_mm.insert(values.at(135));
  }
  EXPECT_EQ(sections, 8);
  EXPECT_EQ(*y_offsets_mm.begin(), -10500) << "section 1 centre, 10.5 m left";
  EXPECT_EQ(*y_offsets_mm.rbegin(), 10500);
  EXPECT_EQ(y_offsets_mm.size(), 8u);

  // Every DDI the ECU implements is a DPD exactly once, on the element element_for_ddi names, and the
  // set-points are settable.
  std::map<std::uint16_t, int> seen;
  for (const auto& p : all_of<DeviceProcessData>(pool)) {
    ++seen[p.ddi];
    const auto element = element_for_ddi(p.ddi);
    ASSERT_TRUE(element.has_value()) << "DDI " << p.ddi;
    EXPECT_EQ(parent_element.at(p.id), *element) << "DDI " << p.ddi;
    const bool setpoint = p.ddi == 6 || p.ddi == 66 || p.ddi == 160 || p.ddi == 289 || p.ddi == 290 ||
                          p.ddi == 389 || (p.ddi >= 57344 && p.ddi <= 57348);  // the proprietary modes
    EXPECT_EQ((p.properties & kPropertySettable) != 0, setpoint) << "DDI " << p.ddi;
    EXPECT_NE(p.triggers, 0) << "DDI " << p.ddi;
  }
  for (const int d : {6, 7, 66, 67, 70, 141, 160, 161, 289, 290, 389, 390, 397, 57344, 57345, 57346, 57347, 57348}) {
    EXPECT_EQ(seen[static_cast<std::uint16_t>(d)], 1) << "DDI " << d;
  }
  EXPECT_FALSE(element_for_ddi(999).has_value());
}

TEST(Ddop, StructureLabelChangesWithTheLayout) {
  const auto label = [](int sections) {
    SpreaderDescription d;
    d.section_count = sections;
    return all_of<DeviceObject>(make_spreader_ddop(d))[0].structure_label;
  };
  EXPECT_NE(label(8), label(6));
  SpreaderDescription too_many_sections;
  too_many_sections.section_count = 17;
  EXPECT_THROW(make_spreader_ddop(too_many_sections), std::invalid_argument);
  SpreaderDescription too_wide;
  too_wide.working_width_m = 60.0;
  EXPECT_THROW(make_spreader_ddop(too_wide), std::invalid_argument);
}

// With a launch table the hopper offers its products: the product set-point (DDI 57349) and one property
// per product (DDI 57350 = k, designator = the material's name), and the structure label changes, so a TC
// holding the pool without them loads it again.
TEST(Ddop, HopperListsTheTablesProducts) {
  SpreaderDescription d;
  d.products = {"urea", "CAN 27 with a name longer than thirty-two bytes"};
  const Ddop pool = make_spreader_ddop(d);
  const DdopParseResult result = parse_ddop(write_ddop(pool));
  ASSERT_TRUE(result.pool) << result.error;
  const Ddop& parsed = *result.pool;
  std::vector<std::string> names;
  for (const DeviceProperty& p : all_of<DeviceProperty>(parsed)) {
    if (p.ddi == 57350) {
      names.push_back(p.designator);
      EXPECT_EQ(p.value, static_cast<std::int32_t>(names.size()));
    }
  }
  ASSERT_EQ(names.size(), 2u);
  EXPECT_EQ(names[0], "urea");
  EXPECT_EQ(names[1].size(), 32u);
  int product_dpd = 0;
  for (const DeviceProcessData& p : all_of<DeviceProcessData>(parsed)) product_dpd += p.ddi == 57349 ? 1 : 0;
  EXPECT_EQ(product_dpd, 1);
  EXPECT_EQ(element_for_ddi(57349), std::optional<std::uint16_t>(2)) << "on the hopper (bin) element";
  EXPECT_NE(all_of<DeviceObject>(pool)[0].structure_label, all_of<DeviceObject>(make_spreader_ddop({}))[0].structure_label);
  SpreaderDescription too_many;
  too_many.products.assign(kMaxListedProducts + 1, "x");
  EXPECT_THROW(make_spreader_ddop(too_many), std::invalid_argument);
}

TEST(Ddop, EveryTruncationIsRefusedWithItsOffset) {
  const std::vector<std::uint8_t> bytes = spreader_bytes(2);
  std::vector<int> accepted_sections;
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    const DdopParseResult r = parse_ddop(std::span<const std::uint8_t>(bytes.data(), n));
    if (!r.pool) {
      EXPECT_FALSE(r.error.empty());
      continue;
    }
    // Sections come last, each a DET and its three DPTs, and the tree is built by parent ID: a prefix that
    // ends after a whole section is a smaller valid pool (the transport's size catches such a cut, not
    // the pool). Any other prefix is refused for a cut object or a dangling reference.
    EXPECT_EQ(write_ddop(*r.pool), std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + static_cast<long>(n)));
    accepted_sections.push_back(static_cast<int>(all_of<DeviceElement>(*r.pool).size()) - 5);
  }
  EXPECT_EQ(accepted_sections, (std::vector<int>{0, 1})) << "only the prefixes with 0 and 1 whole sections";
  EXPECT_NE(parse_ddop(std::span<const std::uint8_t>(bytes.data(), 10)).error.find("byte 0"), std::string::npos);
}

struct BadPool {
  const char* name;
  void (*spoil)(Ddop&);
  const char* expected;
};

class DdopBadPool : public ::testing::TestWithParam<BadPool> {};

TEST_P(DdopBadPool, IsRefusedNamingTheProblem) {
  SpreaderDescription d;
  d.section_count = 2;
  Ddop pool = make_spreader_ddop(d);
  GetParam().spoil(pool);
  const DdopParseResult r = parse_ddop(write_ddop(pool));
  ASSERT_FALSE(r.pool.has_value());
  EXPECT_NE(r.error.find(GetParam().expected), std::string::npos) << r.error;
}

DeviceElement& element_named(Ddop& pool, const std::string& designator) {
  for (auto& o : pool.objects) {
    if (auto* e = std::get_if<DeviceElement>(&o); e && e->designator == designator) return *e;
  }
  throw std::logic_error("no element " + designator);
}

INSTANTIATE_TEST_SUITE_P(
    AllClasses, DdopBadPool,
    ::testing::Values(
        BadPool{"duplicate_id", [](Ddop& p) { element_named(p, "Hopper").id = 0; }, "used twice"},
        BadPool{"dangling_child", [](Ddop& p) { element_named(p, "Hopper").children.push_back(4242); }, "child 4242"},
        BadPool{"child_is_an_element",
                [](Ddop& p) { element_named(p, "Spreader").children.push_back(element_named(p, "Hopper").id); },
                "not a DPD or DPT"},
        BadPool{"child_is_a_presentation", [](Ddop& p) { element_named(p, "Hopper").children.push_back(10); },
                "child 10"},
        BadPool{"section_parent_missing", [](Ddop& p) { element_named(p, "Section 1").parent_id = 999; },
                "not a device element"},
        BadPool{"parent_cycle",
                [](Ddop& p) {
                  element_named(p, "Boom").parent_id = element_named(p, "Section 1").id;
                },
                "does not lead to the device element"},
        BadPool{"element_number_twice", [](Ddop& p) { element_named(p, "Section 2").element_number = 4; },
                "element number 4 used twice"},
        BadPool{"element_number_13_bits", [](Ddop& p) { element_named(p, "Section 2").element_number = 5000; },
                "exceeds 12 bits"},
        BadPool{"second_device_element", [](Ddop& p) { element_named(p, "Discs").type = ElementType::kDevice; },
                "must have the DVC as parent"},
        BadPool{"no_dvc", [](Ddop& p) { p.objects.erase(p.objects.begin()); }, "must have the DVC as parent"},
        BadPool{"presentation_not_a_dvp",
                [](Ddop& p) {
                  for (auto& o : p.objects) {
                    if (auto* d = std::get_if<DeviceProcessData>(&o)) d->presentation_id = 1;
                  }
                },
                "not a DVP"},
        BadPool{"reserved_id", [](Ddop& p) { element_named(p, "Hopper").id = 0xFFFF; }, "reserved"}),
    [](const ::testing::TestParamInfo<BadPool>& param_info) { return std::string(param_info.param.name); });

TEST(Ddop, UnknownTagAndTrailingGarbageAreRefused) {
  std::vector<std::uint8_t> bytes = spreader_bytes(1);
  bytes.insert(bytes.end(), {'X', 'Y', 'Z', 0, 0});
  const DdopParseResult r = parse_ddop(bytes);
  ASSERT_FALSE(r.pool.has_value());
  EXPECT_NE(r.error.find("unknown object type 'XYZ'"), std::string::npos) << r.error;
}

}  // namespace
}  // namespace spread::firmware::can
