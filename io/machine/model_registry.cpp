#include "io/machine/model_registry.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <mutex>
#include <stdexcept>
#include <utility>

#include "io/format/csv.hpp"

namespace pkmopt {
namespace {

struct Registry {
  std::mutex mutex;
  std::vector<std::unique_ptr<ModelEntry>> entries;  // stable addresses

  Registry() {
    add(hexapod_model_entry());
    for (ModelEntry& entry : leg_chain_model_entries()) add(std::move(entry));
    add(lathe_model_entry());
    add(hybrid_model_entry());
    add(serial_model_entry());
  }
  void add(ModelEntry entry) { entries.push_back(std::make_unique<ModelEntry>(std::move(entry))); }
};

Registry& registry() {
  static Registry instance;
  return instance;
}

}  // namespace

const ModelEntry* find_model(std::string_view name) {
  Registry& r = registry();
  const std::lock_guard lock(r.mutex);
  for (const auto& entry : r.entries)
    if (entry->name == name) return entry.get();
  return nullptr;
}

const ModelEntry& machine_model(const YamlValue& model_value) {
  const std::string name = model_value.as_string();
  const ModelEntry* entry = find_model(name);
  if (entry == nullptr || !entry->load)
    model_value.fail(fmt::format("a known model ({})", machine_model_names()), quote_found(name));
  return *entry;
}

SynthesisBody steel_link(std::string key, double area, double length) {
  return {std::move(key), 7850.0 * area * length, length};
}

std::string synthesis_masses_yaml(const SynthesisScale& scale,
                                  const std::vector<SynthesisBody>& legs) {
  if (!scale.masses) return {};
  std::string text =
      "masses:\n"
      "  platform: {mass: 40, inertia: [0.8, 0.8, 0.5, 0, 0, 0]}\n"
      "  legs:\n";
  for (const SynthesisBody& b : legs) {
    if (b.length == 0.0) {
      text += fmt::format("    {}: {{mass: {:.4g}}}\n", b.key, b.mass);
      continue;
    }
    text += fmt::format("    {}: {{mass: {:.4g}, centre: {:.4g}, inertia: {:.4g}}}\n", b.key,
                        b.mass, 0.5 * b.length, b.mass * b.length * b.length / 12.0);
  }
  return text;
}

std::vector<const ModelEntry*> registered_models() {
  Registry& r = registry();
  const std::lock_guard lock(r.mutex);
  std::vector<const ModelEntry*> out;
  for (const auto& entry : r.entries) out.push_back(entry.get());
  return out;
}

std::string machine_model_names() {
  std::string names;
  for (const ModelEntry* entry : registered_models())
    if (entry->load) names += (names.empty() ? "" : ", ") + entry->name;
  return names;
}

ModelRegistration::ModelRegistration(ModelEntry entry) : name_(entry.name) {
  if (name_.empty()) throw std::invalid_argument("ModelRegistration: the model needs a name");
  if (entry.load && !entry.describe && !entry.platform_dofs)
    throw std::invalid_argument("ModelRegistration: model '" + name_ +
                                "' needs platform_dofs or describe (pkmopt describe)");
  Registry& r = registry();
  const std::lock_guard lock(r.mutex);
  for (const auto& e : r.entries)
    if (e->name == name_)
      throw std::invalid_argument("ModelRegistration: a model named '" + name_ +
                                  "' is registered already");
  r.add(std::move(entry));
}

ModelRegistration::~ModelRegistration() {
  Registry& r = registry();
  const std::lock_guard lock(r.mutex);
  std::erase_if(r.entries, [&](const auto& e) { return e->name == name_; });
}

}  // namespace pkmopt
