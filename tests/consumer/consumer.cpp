// Uses the installed pkmopt layers: a machine file (io), a pose (models) and a study (studies).
// Usage: consumer MACHINE.yaml STUDY.yaml OUT_DIR. Prints the TCP stiffness at the home pose and
// the number of designs of the study's front; exits 1 when either looks wrong.
#include <cmath>
#include <iostream>
#include <memory>

#include "io/format/input_error.hpp"
#include "io/machine/machine_file.hpp"
#include "models/core/machine.hpp"
#include "studies/run_study.hpp"

int main(int argc, char** argv) {
  if (argc != 4) {
    std::cerr << "usage: consumer MACHINE.yaml STUDY.yaml OUT_DIR\n";
    return 2;
  }
  try {
    const std::unique_ptr<pkmopt::Machine> machine = pkmopt::load_machine_file(argv[1]);
    const std::unique_ptr<pkmopt::MachineData> data = machine->make_data();
    pkmopt::Pose pose;
    pose.position = {0.0, 0.0, 0.9};
    pkmopt::PoseMetrics metrics;
    machine->analyze(*data, pose, pkmopt::Wrench::Zero(), metrics);
    std::cout << "stiffness_min " << metrics.stiffness_min << " N/m, reachable "
              << metrics.reachable << "\n";
    pkmopt::StudyRunOptions options;
    options.out = argv[3];
    options.force = true;
    options.show_progress = false;
    const pkmopt::StudyRunResult result = pkmopt::run_study_file(argv[2], options);
    std::cout << result.name << ": " << result.designs << " design(s), status " << result.status
              << "\n";
    const bool ok = metrics.reachable && std::isfinite(metrics.stiffness_min) &&
                    metrics.stiffness_min > 0.0 && result.designs > 0 && result.status == "ok";
    return ok ? 0 : 1;
  } catch (const pkmopt::InputError& e) {
    std::cerr << "consumer: " << e.what() << "\n";
    return 2;
  }
}
