// Tests of problems/design/actuator_catalog: which entry carries a load, the order of choice, and
// the checks of a catalog.
#include "problems/design/actuator_catalog.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "tests/sample_catalogs.hpp"

namespace pkmopt {
namespace {

TEST(ActuatorCatalog, ChoosesTheSmallestDriveThatCarriesTheLoad) {
  const ActuatorCatalog catalog = sample_catalogs::sew_cms();
  EXPECT_EQ(check_actuator_catalog(catalog), "");
  // The lathe's turning load (6633 N) over a 180 mm stroke: CMS50S is too weak, CMS63S/200 fits.
  ActuatorChoice choice = choose_actuator(catalog, {6633.0, 0.18, 0.0, 0.0});
  ASSERT_NE(choice.entry, nullptr);
  EXPECT_EQ(choice.entry->name, "CMS63S/200");
  EXPECT_NEAR(choice.force_reserve, 10500.0 / 6633.0, 1e-15);
  // A light load with a short stroke: the shortest CMS50S.
  choice = choose_actuator(catalog, {2000.0, 0.05, 0.3, 0.0});
  ASSERT_NE(choice.entry, nullptr);
  EXPECT_EQ(choice.entry->name, "CMS50S/70");
  // 300 mm stroke and 8 kN: only CMS71L/350 (17000 N) has both.
  choice = choose_actuator(catalog, {8000.0, 0.30, 0.0, 0.0});
  ASSERT_NE(choice.entry, nullptr);
  EXPECT_EQ(choice.entry->name, "CMS71L/350");
  // 18 kN with 300 mm: none (the long CMS71L is rated 17 kN, the strong one is short).
  choice = choose_actuator(catalog, {18000.0, 0.30, 0.0, 0.0});
  EXPECT_EQ(choice.entry, nullptr);
  EXPECT_EQ(choice.reason,
            "no single entry has force >= 18000 N, stroke >= 0.3 m and speed >= 0 m/s");
  choice = choose_actuator(catalog, {25000.0, 0.1, 0.0, 0.0});
  EXPECT_EQ(choice.entry, nullptr);
  EXPECT_EQ(choice.reason, "force 25000 N exceeds the strongest entry (20000 N)");
  choice = choose_actuator(catalog, {1000.0, 0.1, 0.6, 0.0});
  EXPECT_EQ(choice.reason, "speed 0.6 m/s exceeds the fastest entry (0.5 m/s)");
  choice = choose_actuator(catalog, {0.0, 0.1, 0.0, 0.0});
  ASSERT_NE(choice.entry, nullptr);
  EXPECT_EQ(choice.force_reserve, std::numeric_limits<double>::infinity());
}

TEST(ActuatorCatalog, CostsOrderTheChoiceWhenGiven) {
  ActuatorCatalog catalog = sample_catalogs::sew_cms();
  // Suppose the CMS71L/200 were on offer cheaper than the CMS63S/200.
  for (auto& e : catalog.entries) e.cost = e.max_force / 1000.0;
  catalog.entries[5].cost = 5.0;
  const ActuatorChoice choice = choose_actuator(catalog, {6633.0, 0.18, 0.0, 0.0});
  ASSERT_NE(choice.entry, nullptr);
  EXPECT_EQ(choice.entry->name, "CMS71L/200");
  EXPECT_EQ(find_actuator(catalog, "CMS63S/100"), &catalog.entries[3]);
  EXPECT_EQ(find_actuator(catalog, "CMS99"), nullptr);
}

// The cost a study chooses by: ranks by force rating (then stroke) without costs, the costs
// when every entry has one, an error when only some have.
TEST(ActuatorCatalog, CostsAreRanksWithoutPricesAndPricesWithThem) {
  ActuatorCatalog catalog = sample_catalogs::sew_cms();
  // 5300 N x {70, 150, 300} mm, 10500 N x {100, 200} mm, 17000 N x 350 mm, 20000 N x 200 mm.
  EXPECT_EQ(actuator_costs(catalog), (std::vector<double>{1, 2, 3, 4, 5, 7, 6}));
  // The rank order is choose_actuator's: for every requirement the chosen entry has the
  // smallest rank among the entries that carry it.
  const std::vector<double> ranks = actuator_costs(catalog);
  for (double force = 0.0; force <= 21000.0; force += 500.0)
    for (double stroke = 0.05; stroke <= 0.40; stroke += 0.05) {
      const ActuatorChoice choice = choose_actuator(catalog, {force, stroke, 0.0, 0.0});
      double best = std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < catalog.entries.size(); ++i)
        if (carries(catalog.entries[i], {force, stroke, 0.0})) best = std::min(best, ranks[i]);
      if (choice.entry == nullptr) {
        EXPECT_EQ(best, std::numeric_limits<double>::infinity()) << force << " " << stroke;
      } else {
        EXPECT_EQ(ranks[static_cast<std::size_t>(choice.entry - catalog.entries.data())], best);
      }
    }
  for (std::size_t i = 0; i < catalog.entries.size(); ++i) catalog.entries[i].cost = 10.0 + i;
  EXPECT_EQ(actuator_costs(catalog)[6], 16.0);
  catalog.entries[2].cost.reset();
  EXPECT_THROW(actuator_costs(catalog), std::invalid_argument);
}

// The force a leg of a given stroke can have: the strongest entry at least that long.
TEST(ActuatorCatalog, ForceCapacityIsTheStrongestEntryLongEnough) {
  const ActuatorCatalog catalog = sample_catalogs::sew_cms();
  EXPECT_EQ(actuator_force_capacity(catalog, 0.05), 20000.0);
  EXPECT_EQ(actuator_force_capacity(catalog, 0.20), 20000.0);
  EXPECT_EQ(actuator_force_capacity(catalog, 0.2001), 17000.0);
  EXPECT_EQ(actuator_force_capacity(catalog, 0.35), 17000.0);
  EXPECT_EQ(actuator_force_capacity(catalog, 0.36), -std::numeric_limits<double>::infinity());
  // A requirement is carried exactly when its force is within the capacity of its stroke.
  for (double force = 0.0; force <= 21000.0; force += 250.0)
    for (double stroke = 0.05; stroke <= 0.40; stroke += 0.025)
      EXPECT_EQ(choose_actuator(catalog, {force, stroke, 0.0, 0.0}).entry != nullptr,
                force <= actuator_force_capacity(catalog, stroke))
          << force << " " << stroke;
}

TEST(ActuatorCatalog, CarriesChecksEveryRequirement) {
  const ActuatorEntry e{"x", "electric_cylinder", 100.0, 0.2, 0.5, {}, {}, {}, {}};
  EXPECT_TRUE(carries(e, {100.0, 0.2, 0.5, 0.0}));
  EXPECT_FALSE(carries(e, {100.1, 0.2, 0.5, 0.0}));
  EXPECT_FALSE(carries(e, {100.0, 0.21, 0.5, 0.0}));
  EXPECT_FALSE(carries(e, {100.0, 0.2, 0.51, 0.0}));
  // A peak need goes against the peak rating, the continuous one when there is none.
  EXPECT_TRUE(carries(e, {50.0, 0.2, 0.5, 100.0}));
  EXPECT_FALSE(carries(e, {50.0, 0.2, 0.5, 100.1}));
  ActuatorEntry peaky = e;
  peaky.peak_force = 250.0;
  EXPECT_TRUE(carries(peaky, {100.0, 0.2, 0.5, 250.0}));
  EXPECT_FALSE(carries(peaky, {100.0, 0.2, 0.5, 250.1}));
  EXPECT_FALSE(carries(peaky, {100.1, 0.2, 0.5, 0.0}));
}

// actuator_overload is force - capacity without peak needs, and <= 0 exactly when choose_actuator
// finds an entry for both forces.
TEST(ActuatorCatalog, OverloadIsTheShortfallOfTheBestEntry) {
  ActuatorCatalog catalog = sample_catalogs::sew_cms();
  for (double force = 0.0; force <= 21000.0; force += 500.0)
    for (double stroke = 0.05; stroke <= 0.40; stroke += 0.05)
      EXPECT_DOUBLE_EQ(actuator_overload(catalog, {force, stroke, 0.0, 0.0}),
                       force - actuator_force_capacity(catalog, stroke));
  // Peak ratings: CMS50S 12 kN, CMS63S 24 kN, CMS71L 40 kN (illustrative, not datasheet values).
  for (ActuatorEntry& e : catalog.entries)
    e.peak_force = e.max_force < 6000 ? 12000.0 : e.max_force < 11000 ? 24000.0 : 40000.0;
  // stroke 0.25: CMS50S/300 falls 1000 N short of the peak; CMS71L/350 has 13 kN to spare.
  EXPECT_DOUBLE_EQ(actuator_overload(catalog, {4000.0, 0.25, 0.0, 13000.0}), -13000.0);
  // stroke 0.15: CMS71L/200, max(4000 - 20000, 13000 - 40000) = -16000.
  EXPECT_DOUBLE_EQ(actuator_overload(catalog, {4000.0, 0.15, 0.0, 13000.0}), -16000.0);
  EXPECT_DOUBLE_EQ(actuator_overload(catalog, {4000.0, 0.40, 0.0, 0.0}),
                   std::numeric_limits<double>::infinity());
  for (double force = 0.0; force <= 21000.0; force += 1500.0)
    for (double peak = 0.0; peak <= 45000.0; peak += 2500.0)
      for (double stroke = 0.05; stroke <= 0.40; stroke += 0.05) {
        const ActuatorRequirement need{force, stroke, 0.0, peak};
        EXPECT_EQ(actuator_overload(catalog, need) <= 0.0,
                  choose_actuator(catalog, need).entry != nullptr)
            << force << " " << peak << " " << stroke;
      }
  // The reserve is the smaller of the two.
  const ActuatorChoice c = choose_actuator(catalog, {4000.0, 0.3, 0.0, 10000.0});
  ASSERT_NE(c.entry, nullptr);
  EXPECT_EQ(c.entry->name, "CMS50S/300");
  EXPECT_DOUBLE_EQ(c.force_reserve, std::min(5300.0 / 4000.0, 12000.0 / 10000.0));
}

TEST(ActuatorCatalog, CheckNamesTheBadEntry) {
  ActuatorCatalog catalog = sample_catalogs::sew_cms();
  catalog.entries[2].stroke = -0.1;
  EXPECT_EQ(check_actuator_catalog(catalog),
            "entry 2 (CMS50S/300): stroke: expected a number > 0, found -0.1");
  catalog = sample_catalogs::sew_cms();
  catalog.entries[1].name = "CMS50S/70";
  EXPECT_EQ(check_actuator_catalog(catalog),
            "entry 1 (CMS50S/70): name: expected a unique name, found a repeat");
  catalog = sample_catalogs::sew_cms();
  catalog.entries[0].stiffness = std::nan("");
  EXPECT_EQ(check_actuator_catalog(catalog),
            "entry 0 (CMS50S/70): stiffness: expected a number > 0, found nan");
  catalog = sample_catalogs::sew_cms();
  catalog.entries[3].peak_force = 9000.0;
  EXPECT_EQ(check_actuator_catalog(catalog),
            "entry 3 (CMS63S/100): peak_force: expected a number >= max_force = 10500, found 9000");
}

// A catalog that prices every drive: the cylinders with a cost each (per kN of rating, plus the
// stroke) and three rotary drives.
ActuatorCatalog priced_catalog() {
  ActuatorCatalog catalog = sample_catalogs::sew_cms();
  for (ActuatorEntry& e : catalog.entries) e.cost = e.max_force / 1000.0 + 10.0 * e.stroke;
  catalog.rotary_entries = {{"M10", "servo_motor", 10.0, 30.0, 3000.0, 4.0},
                            {"M40", "gear_motor", 40.0, {}, 300.0, 9.0},
                            {"M40b", "gear_motor", 40.0, 100.0, 500.0, 9.0},
                            {"T200", "torque_motor", 200.0, 350.0, 200.0, 30.0}};
  return catalog;
}

// Each group gets the cheapest carrying entry of its kind; the cost is count x the entry's; the
// overload is the least relative shortfall, <= 0 exactly when an entry carries.
TEST(ActuatorCatalog, EveryDrivePricedByItsGroup) {
  const ActuatorCatalog catalog = priced_catalog();
  EXPECT_EQ(check_actuator_catalog(catalog), "");
  EXPECT_EQ(check_drive_pricing(catalog), "");
  EXPECT_DOUBLE_EQ(drive_cost_none(catalog), 60.0);  // twice T200's 30
  // 6 legs: CMS63S/200 (10.5 + 2 = 12.5); 2 motors: M40 (9; M40b ties, later); 1 motor: none (60).
  const std::vector<DriveGroupNeed> needs = {
      {.count = 6, .force = 6633.0, .stroke = 0.18, .drives = {0, 1, 2, 3, 4, 5}},
      {.revolute = true, .count = 2, .force = 25.0, .drives = {6, 8}},
      {.revolute = true, .count = 1, .force = 250.0, .drives = {7}}};
  const DriveChoice choice = choose_drives(catalog, needs);
  ASSERT_EQ(choice.groups.size(), 3u);
  EXPECT_EQ(choice.groups[0].entry, 4);
  EXPECT_DOUBLE_EQ(choice.groups[0].cost, 6 * 12.5);
  // The least shortfall is CMS71L/350's: max(6633/17000, 0.18/0.35) - 1.
  EXPECT_DOUBLE_EQ(choice.groups[0].overload, 0.18 / 0.35 - 1.0);
  EXPECT_EQ(choice.groups[1].entry, 1);
  EXPECT_DOUBLE_EQ(choice.groups[1].cost, 18.0);
  EXPECT_DOUBLE_EQ(choice.groups[1].overload, 25.0 / 200.0 - 1.0);  // T200 carries it best
  EXPECT_EQ(choice.groups[2].entry, -1);
  EXPECT_DOUBLE_EQ(choice.groups[2].cost, 60.0);
  EXPECT_DOUBLE_EQ(choice.groups[2].overload, 250.0 / 200.0 - 1.0);
  EXPECT_DOUBLE_EQ(choice.cost, 75.0 + 18.0 + 60.0);
  // In words, with the drives' numbers (from 1): a run, a list, one drive.
  EXPECT_EQ(drive_choice_text(catalog, needs, choice),
            "q1-q6 6 x CMS63S/200; q7,q9 2 x M40; q8 none");
  EXPECT_DOUBLE_EQ(choice.overload, 0.25);
  // A peak against the peak ratings (the continuous one when none is given): 60 N*m peak is
  // beyond M40 (no peak rating: 40) and within M40b's 100.
  const DriveChoice peak =
      choose_drives(catalog, {{.revolute = true, .force = 25.0, .peak_force = 60.0, .drives = {}}});
  EXPECT_EQ(peak.groups[0].entry, 2);
  // The overload's sign and the choice agree over a grid, for both kinds.
  for (double force = 0.0; force <= 21000.0; force += 1500.0)
    for (double stroke = 0.05; stroke <= 0.40; stroke += 0.05) {
      const DriveChoice c =
          choose_drives(catalog, {{.force = force, .stroke = stroke, .drives = {}}});
      EXPECT_EQ(c.overload <= 0.0, c.groups[0].entry >= 0) << force << " " << stroke;
      const ActuatorChoice one = choose_actuator(catalog, {force, stroke, 0.0, 0.0});
      EXPECT_EQ(one.entry != nullptr, c.groups[0].entry >= 0) << force << " " << stroke;
    }
  for (double torque = 0.0; torque <= 260.0; torque += 5.0) {
    const DriveChoice c =
        choose_drives(catalog, {{.revolute = true, .force = torque, .drives = {}}});
    EXPECT_EQ(c.overload <= 0.0, c.groups[0].entry >= 0) << torque;
  }
  EXPECT_DOUBLE_EQ(choose_drives(catalog, {}).cost, 0.0);
  EXPECT_DOUBLE_EQ(choose_drives(catalog, {}).overload, 0.0);
}

TEST(ActuatorCatalog, EveryDrivePricingNeedsEveryCost) {
  ActuatorCatalog catalog = priced_catalog();
  catalog.rotary_entries[1].cost.reset();
  EXPECT_EQ(check_drive_pricing(catalog), "rotary entry M40: cost: expected a cost, found none");
  catalog = priced_catalog();
  catalog.entries[0].cost.reset();
  EXPECT_EQ(check_drive_pricing(catalog), "entry CMS50S/70: cost: expected a cost, found none");
  catalog = priced_catalog();
  catalog.rotary_entries[2].name = "CMS50S/70";
  EXPECT_EQ(check_actuator_catalog(catalog),
            "rotary entry 2 (CMS50S/70): name: expected a unique name, found a repeat");
  catalog = priced_catalog();
  catalog.rotary_entries[3].peak_torque = 150.0;
  EXPECT_EQ(check_actuator_catalog(catalog),
            "rotary entry 3 (T200): peak_torque: expected a number >= max_torque = 200, found 150");
  catalog = priced_catalog();
  catalog.rotary_entries[0].max_torque = 0.0;
  EXPECT_EQ(check_actuator_catalog(catalog),
            "rotary entry 0 (M10): max_torque: expected a number > 0, found 0");
  EXPECT_EQ(find_rotary(catalog, "T200"), &catalog.rotary_entries[3]);
  EXPECT_EQ(find_rotary(catalog, "CMS50S/70"), nullptr);
}

// A drive carries a path's duty when the peak is within the peak rating (the continuous one when
// there is none), the RMS within the continuous rating, and speed and stroke within the entry's.
TEST(ActuatorCatalog, DriveCheckOfAPathDuty) {
  ActuatorEntry e{"x", "electric_cylinder", 1000.0, 0.2, 0.5, {}, {}, {}, {}};
  const DriveDuty duty{.peak_force = 1500.0, .rms_force = 900.0, .speed = 0.4, .stroke = 0.15};
  DriveCheck c = check_drive(e, duty);
  EXPECT_EQ(c.peak_rating, 1000.0);
  EXPECT_FALSE(c.peak_ok);
  EXPECT_TRUE(c.rms_ok && c.speed_ok && c.stroke_ok);
  EXPECT_FALSE(c.carries());
  e.peak_force = 1500.0;
  c = check_drive(e, duty);
  EXPECT_EQ(c.peak_rating, 1500.0);
  EXPECT_TRUE(c.carries());
  EXPECT_FALSE(check_drive(e, {1500.0, 1000.1, 0.4, 0.15}).rms_ok);
  EXPECT_FALSE(check_drive(e, {1500.0, 900.0, 0.51, 0.15}).speed_ok);
  EXPECT_FALSE(check_drive(e, {1500.0, 900.0, 0.4, 0.21}).stroke_ok);
}

}  // namespace
}  // namespace pkmopt
