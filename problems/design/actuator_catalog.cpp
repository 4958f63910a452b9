#include "problems/design/actuator_catalog.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <tuple>
#include <utility>

namespace pkmopt {
namespace {

bool positive(double v) { return std::isfinite(v) && v > 0.0; }

// Sort key of an entry: cost (or force rating when the catalog has no costs), force, stroke.
std::tuple<double, double, double> order_key(const ActuatorEntry& e, bool use_cost) {
  return {use_cost ? e.cost.value_or(std::numeric_limits<double>::infinity()) : e.max_force,
          e.max_force, e.stroke};
}

}  // namespace

std::string check_actuator_catalog(const ActuatorCatalog& catalog) {
  std::set<std::string> names;
  for (std::size_t i = 0; i < catalog.entries.size(); ++i) {
    const ActuatorEntry& e = catalog.entries[i];
    const std::string where = fmt::format("entry {} ({})", i, e.name.empty() ? "unnamed" : e.name);
    if (e.name.empty()) return where + ": name: expected a non-empty name";
    if (!names.insert(e.name).second)
      return where + ": name: expected a unique name, found a repeat";
    if (!positive(e.max_force))
      return fmt::format("{}: max_force: expected a number > 0, found {}", where, e.max_force);
    if (!positive(e.stroke))
      return fmt::format("{}: stroke: expected a number > 0, found {}", where, e.stroke);
    if (!positive(e.max_speed))
      return fmt::format("{}: max_speed: expected a number > 0, found {}", where, e.max_speed);
    const std::pair<const char*, const std::optional<double>*> optional_values[] = {
        {"accuracy", &e.accuracy},
        {"stiffness", &e.stiffness},
        {"cost", &e.cost},
        {"peak_force", &e.peak_force}};
    for (const auto& [key, value] : optional_values) {
      if (*value && !positive(**value))
        return fmt::format("{}: {}: expected a number > 0, found {}", where, key, **value);
    }
    if (e.peak_force && *e.peak_force < e.max_force)
      return fmt::format("{}: peak_force: expected a number >= max_force = {}, found {}", where,
                         e.max_force, *e.peak_force);
  }
  for (std::size_t i = 0; i < catalog.rotary_entries.size(); ++i) {
    const RotaryEntry& e = catalog.rotary_entries[i];
    const std::string where =
        fmt::format("rotary entry {} ({})", i, e.name.empty() ? "unnamed" : e.name);
    if (e.name.empty()) return where + ": name: expected a non-empty name";
    if (!names.insert(e.name).second)
      return where + ": name: expected a unique name, found a repeat";
    if (!positive(e.max_torque))
      return fmt::format("{}: max_torque: expected a number > 0, found {}", where, e.max_torque);
    if (!positive(e.max_speed_rpm))
      return fmt::format("{}: max_speed: expected a number > 0, found {}", where, e.max_speed_rpm);
    if (e.cost && !positive(*e.cost))
      return fmt::format("{}: cost: expected a number > 0, found {}", where, *e.cost);
    if (e.peak_torque && !(positive(*e.peak_torque) && *e.peak_torque >= e.max_torque))
      return fmt::format("{}: peak_torque: expected a number >= max_torque = {}, found {}", where,
                         e.max_torque, *e.peak_torque);
  }
  return {};
}

DriveCheck check_drive(const ActuatorEntry& entry, const DriveDuty& duty) {
  DriveCheck check;
  check.peak_rating = entry.peak_force.value_or(entry.max_force);
  check.peak_ok = duty.peak_force <= check.peak_rating;
  check.rms_ok = duty.rms_force <= entry.max_force;
  check.speed_ok = duty.speed <= entry.max_speed;
  check.stroke_ok = duty.stroke <= entry.stroke;
  return check;
}

bool carries(const ActuatorEntry& entry, const ActuatorRequirement& need) {
  return entry.max_force >= need.force && entry.stroke >= need.stroke &&
         entry.max_speed >= need.speed &&
         entry.peak_force.value_or(entry.max_force) >= need.peak_force;
}

ActuatorChoice choose_actuator(const ActuatorCatalog& catalog, const ActuatorRequirement& need) {
  bool any_cost = false;
  for (const ActuatorEntry& e : catalog.entries) any_cost = any_cost || e.cost.has_value();
  ActuatorChoice choice;
  for (const ActuatorEntry& e : catalog.entries) {
    if (!carries(e, need)) continue;
    if (choice.entry == nullptr || order_key(e, any_cost) < order_key(*choice.entry, any_cost)) {
      choice.entry = &e;
    }
  }
  if (choice.entry != nullptr) {
    const ActuatorEntry& e = *choice.entry;
    constexpr double kInf = std::numeric_limits<double>::infinity();
    choice.force_reserve = std::min(
        need.force > 0.0 ? e.max_force / need.force : kInf,
        need.peak_force > 0.0 ? e.peak_force.value_or(e.max_force) / need.peak_force : kInf);
    return choice;
  }
  double best_force = 0.0, best_stroke = 0.0, best_speed = 0.0, best_peak = 0.0;
  for (const ActuatorEntry& e : catalog.entries) {
    best_force = std::max(best_force, e.max_force);
    best_peak = std::max(best_peak, e.peak_force.value_or(e.max_force));
    best_stroke = std::max(best_stroke, e.stroke);
    best_speed = std::max(best_speed, e.max_speed);
  }
  if (catalog.entries.empty()) {
    choice.reason = "the catalog has no entries";
  } else if (best_force < need.force) {
    choice.reason = fmt::format("force {:.6g} N exceeds the strongest entry ({:.6g} N)", need.force,
                                best_force);
  } else if (best_peak < need.peak_force) {
    choice.reason = fmt::format("peak force {:.6g} N exceeds the strongest entry's peak ({:.6g} N)",
                                need.peak_force, best_peak);
  } else if (best_stroke < need.stroke) {
    choice.reason = fmt::format("stroke {:.6g} m exceeds the longest entry ({:.6g} m)", need.stroke,
                                best_stroke);
  } else if (best_speed < need.speed) {
    choice.reason = fmt::format("speed {:.6g} m/s exceeds the fastest entry ({:.6g} m/s)",
                                need.speed, best_speed);
  } else {
    choice.reason = fmt::format(
        "no single entry has force >= {:.6g} N, stroke >= {:.6g} m and speed >= {:.6g} m/s",
        need.force, need.stroke, need.speed);
  }
  return choice;
}

std::vector<double> actuator_costs(const ActuatorCatalog& catalog) {
  std::size_t with_cost = 0;
  for (const ActuatorEntry& e : catalog.entries) with_cost += e.cost.has_value() ? 1 : 0;
  std::vector<double> costs(catalog.entries.size());
  if (with_cost == catalog.entries.size()) {
    for (std::size_t i = 0; i < costs.size(); ++i) costs[i] = *catalog.entries[i].cost;
    return costs;
  }
  if (with_cost > 0)
    throw std::invalid_argument(
        fmt::format("catalog '{}': expected a cost for every entry or for none, found {} of {}",
                    catalog.name, with_cost, catalog.entries.size()));
  std::vector<std::size_t> order(catalog.entries.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return order_key(catalog.entries[a], false) < order_key(catalog.entries[b], false);
  });
  for (std::size_t rank = 0; rank < order.size(); ++rank)
    costs[order[rank]] = static_cast<double>(rank + 1);
  return costs;
}

double actuator_overload(const ActuatorCatalog& catalog, const ActuatorRequirement& need) {
  double overload = std::numeric_limits<double>::infinity();
  for (const ActuatorEntry& e : catalog.entries) {
    if (e.stroke < need.stroke) continue;
    overload = std::min(overload, std::max(need.force - e.max_force,
                                           need.peak_force - e.peak_force.value_or(e.max_force)));
  }
  return overload;
}

double actuator_force_capacity(const ActuatorCatalog& catalog, double stroke) {
  double capacity = -std::numeric_limits<double>::infinity();
  for (const ActuatorEntry& e : catalog.entries)
    if (e.stroke >= stroke) capacity = std::max(capacity, e.max_force);
  return capacity;
}

std::string check_drive_pricing(const ActuatorCatalog& catalog) {
  for (const ActuatorEntry& e : catalog.entries)
    if (!e.cost) return fmt::format("entry {}: cost: expected a cost, found none", e.name);
  for (const RotaryEntry& e : catalog.rotary_entries)
    if (!e.cost) return fmt::format("rotary entry {}: cost: expected a cost, found none", e.name);
  if (catalog.entries.empty() && catalog.rotary_entries.empty())
    return "expected at least one entry, found none";
  return {};
}

double drive_cost_none(const ActuatorCatalog& catalog) {
  double dearest = 0.0;
  for (const ActuatorEntry& e : catalog.entries) dearest = std::max(dearest, e.cost.value_or(0.0));
  for (const RotaryEntry& e : catalog.rotary_entries)
    dearest = std::max(dearest, e.cost.value_or(0.0));
  return 2.0 * dearest;
}

namespace {

// How far an entry falls short of a group's need, relative: <= 0 when it carries.
double linear_shortfall(const ActuatorEntry& e, const DriveGroupNeed& need) {
  return std::max({need.force / e.max_force, need.peak_force / e.peak_force.value_or(e.max_force),
                   need.stroke / e.stroke}) -
         1.0;
}

double rotary_shortfall(const RotaryEntry& e, const DriveGroupNeed& need) {
  return std::max(need.force / e.max_torque,
                  need.peak_force / e.peak_torque.value_or(e.max_torque)) -
         1.0;
}

// The cheapest carrying entry of a list (ties: the smaller rating, then the list order) and the
// least shortfall.
template <class Entry, class Shortfall, class Rating>
DriveGroupChoice choose_group(const std::vector<Entry>& entries, const DriveGroupNeed& need,
                              Shortfall shortfall, Rating rating) {
  DriveGroupChoice choice;
  choice.overload = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const Entry& e = entries[i];
    const double s = shortfall(e, need);
    choice.overload = std::min(choice.overload, s);
    if (s > 0.0) continue;
    if (choice.entry < 0) {
      choice.entry = static_cast<int>(i);
      continue;
    }
    const Entry& best = entries[static_cast<std::size_t>(choice.entry)];
    if (std::pair(*e.cost, rating(e)) < std::pair(*best.cost, rating(best)))
      choice.entry = static_cast<int>(i);
  }
  return choice;
}

}  // namespace

DriveChoice choose_drives(const ActuatorCatalog& catalog,
                          const std::vector<DriveGroupNeed>& needs) {
  DriveChoice out;
  out.overload = -std::numeric_limits<double>::infinity();
  const double none = drive_cost_none(catalog);
  for (const DriveGroupNeed& need : needs) {
    DriveGroupChoice group = need.revolute
                                 ? choose_group(catalog.rotary_entries, need, rotary_shortfall,
                                                [](const RotaryEntry& e) { return e.max_torque; })
                                 : choose_group(catalog.entries, need, linear_shortfall,
                                                [](const ActuatorEntry& e) { return e.max_force; });
    double unit = none;
    if (group.entry >= 0) {
      const auto i = static_cast<std::size_t>(group.entry);
      unit = need.revolute ? *catalog.rotary_entries[i].cost : *catalog.entries[i].cost;
    }
    group.cost = need.count * unit;
    out.cost += group.cost;
    out.overload = std::max(out.overload, group.overload);
    out.groups.push_back(group);
  }
  if (needs.empty()) out.overload = 0.0;
  return out;
}

std::string drive_choice_text(const ActuatorCatalog& catalog,
                              const std::vector<DriveGroupNeed>& needs, const DriveChoice& choice) {
  std::string text;
  for (std::size_t g = 0; g < needs.size() && g < choice.groups.size(); ++g) {
    const DriveGroupNeed& need = needs[g];
    const int entry = choice.groups[g].entry;
    std::string name = "none";
    if (entry >= 0)
      name = need.revolute ? catalog.rotary_entries[static_cast<std::size_t>(entry)].name
                           : catalog.entries[static_cast<std::size_t>(entry)].name;
    std::string drives;  // q3-q5 for a run, q1,q4 otherwise
    const std::vector<int>& d = need.drives;
    bool run = d.size() > 2;
    for (std::size_t k = 1; k < d.size(); ++k) run = run && d[k] == d[k - 1] + 1;
    if (run) {
      drives = fmt::format("q{}-q{}", d.front() + 1, d.back() + 1);
    } else {
      for (const int i : d) drives += fmt::format("{}q{}", drives.empty() ? "" : ",", i + 1);
    }
    text += fmt::format("{}{}{}{}", text.empty() ? "" : "; ", drives, drives.empty() ? "" : " ",
                        need.count > 1 ? fmt::format("{} x {}", need.count, name) : name);
  }
  return text;
}

const RotaryEntry* find_rotary(const ActuatorCatalog& catalog, const std::string& name) {
  for (const RotaryEntry& e : catalog.rotary_entries)
    if (e.name == name) return &e;
  return nullptr;
}

const ActuatorEntry* find_actuator(const ActuatorCatalog& catalog, const std::string& name) {
  for (const ActuatorEntry& e : catalog.entries) {
    if (e.name == name) return &e;
  }
  return nullptr;
}

CatalogPricing catalog_pricing(const ActuatorCatalog& catalog) {
  CatalogPricing pricing;
  pricing.cost = actuator_costs(catalog);
  pricing.none = !catalog.entries.empty() && catalog.entries.front().cost
                     ? 2.0 * *std::max_element(pricing.cost.begin(), pricing.cost.end())
                     : static_cast<double>(catalog.entries.size() + 1);
  return pricing;
}

StudyActuatorChoice study_actuator_choice(const ActuatorCatalog& catalog,
                                          const CatalogPricing& pricing,
                                          const ActuatorRequirement& need) {
  StudyActuatorChoice out;
  out.overload = actuator_overload(catalog, need);
  const ActuatorChoice choice = choose_actuator(catalog, need);
  if (choice.entry == nullptr) {
    out.cost = pricing.none;
    return out;
  }
  out.entry = static_cast<int>(choice.entry - catalog.entries.data());
  out.cost = pricing.cost[static_cast<std::size_t>(out.entry)];
  return out;
}

}  // namespace pkmopt
