// Actuator catalogs: the linear drives a leg can be built from, and the choice of the entry
// that carries a load.
//
// An entry is one orderable variant: a name ("SEW CMS63S/200"), the drive type, the largest
// continuous axial force it carries (N), its stroke (m), maximum speed (m/s) and, when known,
// positioning accuracy (m), axial stiffness (N/m) and a relative cost (any positive unit; when
// no entry of a catalog has one, the force rating orders the entries: a stronger drive of the
// same family is the bigger, dearer one).
//
//   const ActuatorCatalog catalog = ...;               // e.g. app/actuator_catalog_file
//   ActuatorRequirement need{.force = 6633.0, .stroke = 0.18};
//   const ActuatorChoice choice = choose_actuator(catalog, need);
//   if (choice.entry) ... choice.entry->name, choice.force_reserve ...
//
// `carries(entry, need)`: max_force >= need.force, stroke >= need.stroke, max_speed >=
// need.speed, peak rating (peak_force, else max_force) >= need.peak_force (each requirement
// optional: 0 means none). The cheapest carrying entry wins; ties
// go to the smaller force rating, then the shorter stroke, then the catalog order.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace pkmopt {

struct ActuatorEntry {
  std::string name;
  std::string type;                 ///< e.g. electric_cylinder, linear_motor, hydraulic
  double max_force = 0.0;           ///< N, continuous (rated) axial force
  double stroke = 0.0;              ///< m
  double max_speed = 0.0;           ///< m/s
  std::optional<double> accuracy;   ///< m, positioning accuracy (repeatability) if known
  std::optional<double> stiffness;  ///< N/m, axial stiffness if known
  std::optional<double> cost;       ///< relative cost if known
  /// N, the short-time peak force when the datasheet gives one (>= max_force); a check against
  /// the peak of a path uses max_force when it is not given.
  std::optional<double> peak_force;
};

/// Typical figures of a drive type (ranges; for comparison tables, not for sizing).
struct DriveType {
  std::string name;
  double speed_min = 0.0, speed_max = 0.0;        ///< m/s
  double accuracy_min = 0.0, accuracy_max = 0.0;  ///< m (best .. worst)
  std::string note;
};

/// A rotary drive (a servo motor, with its gearbox when it has one): the revolute actuators (a
/// delta's cranks, a serial machine's rotary axes) are chosen from these. Figures at the output
/// shaft.
struct RotaryEntry {
  std::string name;
  std::string type;                   ///< e.g. servo_motor, gear_motor, torque_motor
  double max_torque = 0.0;            ///< N*m, continuous (rated) torque
  std::optional<double> peak_torque;  ///< N*m, short-time peak (>= max_torque)
  double max_speed_rpm = 0.0;         ///< 1/min, maximum speed
  std::optional<double> cost;         ///< relative cost if known
};

struct ActuatorCatalog {
  std::string name;
  std::vector<ActuatorEntry> entries;       ///< linear drives
  std::vector<RotaryEntry> rotary_entries;  ///< rotary drives (priced per drive only)
  std::vector<DriveType> drive_types;
};

/// What one leg must do (0 = no requirement).
struct ActuatorRequirement {
  double force = 0.0;   ///< N, largest |axial force| over the task (against max_force)
  double stroke = 0.0;  ///< m, max_length - min_length
  double speed = 0.0;   ///< m/s
  /// N, the largest short-time force (rapid moves: actuator_force_dynamic_max), against the
  /// entry's peak rating (peak_force, or max_force when it has none).
  double peak_force = 0.0;
};

struct ActuatorChoice {
  const ActuatorEntry* entry = nullptr;  ///< null when no entry carries the requirement
  /// The smaller of max_force / need.force and peak rating / need.peak_force (inf when there is
  /// no force need).
  double force_reserve = 0.0;
  std::string reason;  ///< when entry is null: the closest miss
};

/// Empty when usable: every entry named, finite positive force (torque), stroke and speed,
/// optional values finite and positive, peaks at least the ratings, names unique across the linear
/// and rotary entries; otherwise what is wrong.
std::string check_actuator_catalog(const ActuatorCatalog& catalog);

bool carries(const ActuatorEntry& entry, const ActuatorRequirement& need);

/// The cheapest entry that carries `need` (see the header comment for the order).
ActuatorChoice choose_actuator(const ActuatorCatalog& catalog, const ActuatorRequirement& need);

/// The relative cost of every entry (catalog order) by which a study chooses: the entries'
/// `cost` when every entry has one; when none has, the rank (1 = cheapest) in the order
/// choose_actuator uses without costs (force rating, then stroke, then catalog order). Throws
/// std::invalid_argument when only some entries have a cost (the order would be a guess).
std::vector<double> actuator_costs(const ActuatorCatalog& catalog);

/// How a design study prices the entries: each entry's cost (actuator_costs) and the cost of a
/// design no entry carries, dearer than every entry (twice the dearest cost; for a rank catalog
/// the rank after the last). Throws std::invalid_argument as actuator_costs does.
struct CatalogPricing {
  std::vector<double> cost;
  double none = 0.0;
};
CatalogPricing catalog_pricing(const ActuatorCatalog& catalog);

/// How far the best entry long enough for need.stroke falls short of the forces (N): the minimum
/// over those entries of max(need.force - max_force, need.peak_force - peak rating); <= 0 exactly
/// when some entry carries both forces and the stroke (speed not considered); +inf when no entry
/// is long enough.
double actuator_overload(const ActuatorCatalog& catalog, const ActuatorRequirement& need);

/// The largest force rating (N) among the entries whose stroke is at least `stroke` (m); -inf
/// when no entry is that long. A leg needing `force` and `stroke` is carried by some entry exactly
/// when force <= actuator_force_capacity(catalog, stroke) (speed not considered).
double actuator_force_capacity(const ActuatorCatalog& catalog, double stroke);

/// A design study's choice for a need: the chosen entry's index (-1 when none carries), its cost
/// (pricing.none when none carries) and actuator_overload(catalog, need).
struct StudyActuatorChoice {
  int entry = -1;
  double cost = 0.0;
  double overload = 0.0;
};
StudyActuatorChoice study_actuator_choice(const ActuatorCatalog& catalog,
                                          const CatalogPricing& pricing,
                                          const ActuatorRequirement& need);

/// What a drive must do along a path (pkmopt trajectory): the peak and RMS axial force over
/// the path (N), the peak speed (m/s) and the stroke it spans (m).
struct DriveDuty {
  double peak_force = 0.0;
  double rms_force = 0.0;
  double speed = 0.0;
  double stroke = 0.0;
};

/// Whether an entry carries a duty: peak force within peak_force (max_force when the entry has
/// none), RMS force within the continuous max_force (the thermal duty of a path repeated
/// without pause), speed within max_speed, stroke within the entry's stroke.
struct DriveCheck {
  double peak_rating = 0.0;  ///< N, the rating the peak was checked against
  bool peak_ok = false;
  bool rms_ok = false;
  bool speed_ok = false;
  bool stroke_ok = false;
  bool carries() const { return peak_ok && rms_ok && speed_ok && stroke_ok; }
};
DriveCheck check_drive(const ActuatorEntry& entry, const DriveDuty& duty);

// ---------------------------------------------------------------------------------------------
// Every drive priced: the drives of a machine fall into groups of alike drives (a parallel
// machine's legs are one group, bought as one entry; a serial axis is a group of its own), and
// each group gets the cheapest entry of its kind (linear or rotary) that carries the group's worst
// drive. The machine's drive cost is the sum over the groups of count x the entry's cost, so that
// structures with different numbers and kinds of drives compare.

/// One group of alike drives and the most any of them must do.
struct DriveGroupNeed {
  bool revolute = false;
  int count = 1;
  double force = 0.0;       ///< N (N*m for revolute drives): the largest |tau| over the task
  double peak_force = 0.0;  ///< N (N*m): the largest short-time force (0: none)
  double stroke = 0.0;      ///< m: linear drives' travel (revolute drives: none)
  std::vector<int> drives;  ///< the machine's drives in the group (0-based), for the text
};

/// The choice for one group: the entry's index (into `entries` or `rotary_entries`; -1 when none
/// carries), the group's cost (count x entry cost, or count x DrivePricing::none) and its
/// relative overload: the minimum over the entries of the kind of
/// max(force / rating, peak / peak rating, stroke / entry stroke) - 1, <= 0 exactly when some
/// entry carries the group (speed not considered).
struct DriveGroupChoice {
  int entry = -1;
  double cost = 0.0;
  double overload = 0.0;
};

struct DriveChoice {
  std::vector<DriveGroupChoice> groups;
  double cost = 0.0;      ///< the sum of the groups' costs
  double overload = 0.0;  ///< the largest group overload (dimensionless)
};

/// Empty when the catalog can price every drive: every entry, linear and rotary, has a cost (the
/// sum compares only costs in one unit); otherwise why not.
std::string check_drive_pricing(const ActuatorCatalog& catalog);

/// The price of a drive no entry carries: twice the dearest cost of the catalog (linear or rotary).
double drive_cost_none(const ActuatorCatalog& catalog);

/// Each group's cheapest carrying entry of its kind (ties: the smaller rating, then the catalog
/// order). Needs check_drive_pricing(catalog) empty; a group whose kind has no entries has
/// overload +inf.
DriveChoice choose_drives(const ActuatorCatalog& catalog, const std::vector<DriveGroupNeed>& needs);

/// The choice in words, group by group: "q1 BSA32/800; q2 BSA32/800; q3-q5 3 x BSA32/500"
/// (drives numbered from 1 as q_1..q_n; "none" where no entry carries; a group without drive
/// numbers is named by its count only).
std::string drive_choice_text(const ActuatorCatalog& catalog,
                              const std::vector<DriveGroupNeed>& needs, const DriveChoice& choice);

/// The rotary entry named `name`, or null.
const RotaryEntry* find_rotary(const ActuatorCatalog& catalog, const std::string& name);

/// The entry named `name`, or null.
const ActuatorEntry* find_actuator(const ActuatorCatalog& catalog, const std::string& name);

}  // namespace pkmopt
