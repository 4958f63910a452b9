// A model of the test's own, registered in the model registry (io/machine/model_registry.hpp), goes
// through the ordinary paths of every command: the machine file is read and described,
// analyzed at poses and written as the analyze CSV, solved by forward kinematics, its workspace
// computed, and a short design study over its design family runs and writes its front and
// machine files. Nothing outside this file knows the model.
//
// The toy: a translational tripod (3-UPU, the platform kept level by its passive joints): base
// joints a_i = r_b (cos t_i, sin t_i, 0), platform joints b_i = r_p (cos t_i, sin t_i, 0),
// t_i = 90 + 120 i deg, prismatic legs q_i = |p + b_i - a_i| in [min_length, max_length] with
// axial stiffness k; the platform above the base (p_z > 0). With u_i the unit leg vectors and
// J the 3x3 matrix of rows u_i^T (q_dot = J v): J^T tau = f (tension positive),
// K = k J^T J, singularity_margin = 1 / cond(J), tcp_error_max = max over dq in {-e, e}^3 of
// |J^-1 dq|.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "io/design/study_machine.hpp"
#include "io/format/field_list.hpp"
#include "io/format/pose_csv.hpp"
#include "io/machine/machine_description.hpp"
#include "io/machine/machine_file.hpp"
#include "io/machine/model_registry.hpp"
#include "io/results/analyze_csv.hpp"
#include "io/results/fk_csv.hpp"
#include "models/core/pose_analysis.hpp"
#include "models/workspace/workspace.hpp"
#include "studies/design_study.hpp"
#include "studies/run_study.hpp"
#include "tests/scratch_dir.hpp"

namespace pkmopt {
namespace {

struct ToyTripodDesign {
  double base_radius = 0.5;
  double platform_radius = 0.15;
  double min_length = 0.6;
  double max_length = 1.0;
  double axial_stiffness = 1.0e7;  // N/m
  double actuator_error = 1.0e-5;  // m
};

template <class Fields>
void describe_fields(Fields& f, ToyTripodDesign& d) {
  f.note("model", "toy_tripod", "", "required", "the machine model");
  const FieldRule positive{.min = 0, .min_exclusive = true, .required = true, .unit = "m"};
  f.field("base_radius", d.base_radius, positive);
  f.field("platform_radius", d.platform_radius, positive);
  f.field("min_length", d.min_length, positive);
  f.field("max_length", d.max_length, positive);
  f.field("axial_stiffness", d.axial_stiffness,
          {.min = 0, .min_exclusive = true, .required = true, .unit = "N/m"});
  f.field("actuator_error", d.actuator_error, {.min = 0, .unit = "m"});
}

std::string toy_machine_file(const ToyTripodDesign& design) {
  FieldWriter writer;
  ToyTripodDesign copy = design;
  describe_fields(writer, copy);
  return "model: toy_tripod\n" + writer.flow_lines();
}

Eigen::Vector3d joint(double radius, int i) {
  const double t = (90.0 + 120.0 * i) * std::numbers::pi / 180.0;
  return {radius * std::cos(t), radius * std::sin(t), 0.0};
}

class ToyTripod final : public Machine {
 public:
  explicit ToyTripod(const ToyTripodDesign& d) : d_(d) {
    if (!(d.max_length > d.min_length))
      throw std::invalid_argument("toy_tripod: max_length must exceed min_length");
  }
  std::string_view model() const override { return "toy_tripod"; }
  int num_actuators() const override { return 3; }
  bool revolute_actuators() const override { return false; }
  std::unique_ptr<MachineData> make_data() const override { return new_data<MachineData>(); }

  // The legs at a position: q_i and the rows u_i^T of J.
  Eigen::Vector3d legs(const Eigen::Vector3d& p, Eigen::Matrix3d& J) const {
    Eigen::Vector3d q;
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d v = p + joint(d_.platform_radius, i) - joint(d_.base_radius, i);
      q(i) = v.norm();
      J.row(i) = v.transpose() / q(i);
    }
    return q;
  }

  bool reachable(MachineData& /*data*/, const Pose& pose) const override {
    if (pose.angles.cwiseAbs().maxCoeff() > 1e-12 || !(pose.position.z() > 0.0)) return false;
    Eigen::Matrix3d J;
    const Eigen::Vector3d q = legs(pose.position, J);
    return q.minCoeff() >= d_.min_length && q.maxCoeff() <= d_.max_length;
  }

  void analyze(MachineData& data, const Pose& pose, const Wrench& wrench,
               PoseMetrics& out) const override {
    Eigen::Matrix3d J;
    out.q = legs(pose.position, J);
    out.reachable = reachable(data, pose);
    out.det_j = J.determinant();
    // 1 / cond(J) from the eigenvalues of J^T J, the squared singular values of J.
    const Eigen::Vector3d sigma2 =
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(J.transpose() * J).eigenvalues();
    const double margin = std::sqrt(std::max(0.0, sigma2(0)) / sigma2(2));
    out.singular = !(margin > 1e-9);
    const double inf = std::numeric_limits<double>::infinity();
    if (out.singular) {
      out.tau = Eigen::Vector3d::Constant(inf);
      out.stiffness_min = out.singularity_margin = out.stiffness_min_loaded = 0.0;
      out.tcp_error_max = out.tcp_deflection = out.tcp_rotation_deflection = inf;
      out.stiffness_min_direction.setZero();
      return;
    }
    const Eigen::Vector3d f = wrench.head<3>();
    out.tau = J.transpose().inverse() * f;
    out.singularity_margin = margin;
    const Eigen::Matrix3d K = d_.axial_stiffness * J.transpose() * J;
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(K);
    out.stiffness_min = eig.eigenvalues()(0);
    double worst = 0.0;
    const Eigen::Matrix3d Jinv = J.inverse();
    for (int s = 0; s < 8; ++s) {
      const Eigen::Vector3d dq(s & 1 ? 1 : -1, s & 2 ? 1 : -1, s & 4 ? 1 : -1);
      worst = std::max(worst, (Jinv * dq * d_.actuator_error).norm());
    }
    out.tcp_error_max = worst;
    out.tcp_deflection = out.tcp_rotation_deflection = out.stiffness_min_loaded = 0.0;
    out.stiffness_min_direction.setZero();
    if (!data.compliance_metrics) return;
    const Eigen::Matrix3d C = K.inverse();
    data.matrices.compliance.setZero();
    data.matrices.compliance.topLeftCorner<3, 3>() = C;
    out.tcp_deflection = (C * f).norm();
    Eigen::Vector3d direction = eig.eigenvectors().col(0);
    Eigen::Index largest = 0;
    direction.cwiseAbs().maxCoeff(&largest);
    out.stiffness_min_direction = direction(largest) < 0 ? Eigen::Vector3d(-direction) : direction;
    Eigen::Matrix3d KT = K;
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d u = J.row(i).transpose();
      KT += out.tau(i) / out.q(i) * (Eigen::Matrix3d::Identity() - u * u.transpose());
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> loaded(KT);
    out.stiffness_min_loaded = std::max(0.0, loaded.eigenvalues()(0));
    data.matrices.loaded_compliance_tt = KT.inverse();
  }

  FkResult forward_kinematics(const Eigen::VectorXd& q, const std::optional<Pose>& guess,
                              const FkOptions& options) const override {
    FkResult r;
    const double mid = 0.5 * (d_.min_length + d_.max_length);
    const double offset = d_.base_radius - d_.platform_radius;
    r.pose.position =
        guess ? guess->position : Eigen::Vector3d(0, 0, std::sqrt(mid * mid - offset * offset));
    for (r.iterations = 0; r.iterations <= options.max_iterations; ++r.iterations) {
      Eigen::Matrix3d J;
      const Eigen::Vector3d residual = legs(r.pose.position, J) - q;
      r.residual = residual.cwiseAbs().maxCoeff();
      if (r.residual <= options.tolerance) {
        r.converged = true;
        return r;
      }
      r.pose.position -= J.partialPivLu().solve(residual);
    }
    r.message = "no convergence";
    return r;
  }

  std::optional<Eigen::AlignedBox3d> workspace_search_box(
      const std::vector<Eigen::Matrix3d>& /*orientations*/) const override {
    const double reach = d_.max_length + d_.base_radius;
    return Eigen::AlignedBox3d(Eigen::Vector3d(-reach, -reach, 0.0),
                               Eigen::Vector3d(reach, reach, d_.max_length));
  }

 private:
  ToyTripodDesign d_;
};

ToyTripodDesign read_toy(const YamlValue& root) {
  ToyTripodDesign d;
  read_fields(root, d);
  if (!(d.max_length > d.min_length))
    root.required("max_length")
        .fail("a number > min_length", root.required("max_length").describe());
  return d;
}

DesignFamily toy_family(const ToyTripodDesign& t) {
  DesignFamily family;
  family.model = "toy_tripod";
  family.translational = true;
  family.parameters = {
      {"base_radius", "m", "base joint circle", t.base_radius, false, false},
      {"platform_radius", "m", "platform joint circle", t.platform_radius, false, false},
      {"min_length", "m", "shortest leg", t.min_length, false, false},
      {"stroke", "m", "max_length - min_length", t.max_length - t.min_length, false, false},
      {"home_height", "m", "task lift along z", 0.0, true, true}};
  family.parameter_keys = {"base_radius", "platform_radius", "min_length", "max_length"};
  auto design = [t](const std::vector<double>& p) {
    ToyTripodDesign d = t;
    d.base_radius = p.at(0);
    d.platform_radius = p.at(1);
    d.min_length = p.at(2);
    d.max_length = p.at(2) + p.at(3);
    return d;
  };
  family.build = [design](const std::vector<double>& p) -> std::unique_ptr<Machine> {
    return std::make_unique<ToyTripod>(design(p));
  };
  family.machine_file = [design](const std::vector<double>& p) {
    return toy_machine_file(design(p));
  };
  family.machine_size = [](const Machine&, const std::vector<double>& p) {
    return std::numbers::pi * p.at(0) * p.at(0) * (p.at(2) + p.at(3));
  };
  return family;
}

ModelEntry toy_entry() {
  ModelEntry entry;
  entry.name = "toy_tripod";
  entry.load = [](const YamlValue& root) -> std::unique_ptr<Machine> {
    return std::make_unique<ToyTripod>(read_toy(root));
  };
  entry.fields_markdown = [] { return fields_markdown(ToyTripodDesign{}); };
  entry.platform_dofs = [](const YamlValue&) { return PlatformDofs{3, 0}; };
  entry.design_family = [](const YamlValue* machine) {
    return toy_family(machine ? read_toy(*machine) : ToyTripodDesign{});
  };
  return entry;
}

class ToyModel : public ::testing::Test {
 protected:
  const ModelRegistration registration_{toy_entry()};
  const scratch::ScratchDir dir_;
  std::string write(const std::string& name, const std::string& text) const {
    const std::filesystem::path path = dir_ / name;
    std::ofstream(path) << text;
    return path.string();
  }
  const std::string file_ = toy_machine_file(ToyTripodDesign{});
};

TEST_F(ToyModel, IsReadDescribedAndAnalyzedThroughTheRegistry) {
  const std::string path = write("toy.yaml", file_);
  const std::unique_ptr<Machine> machine = load_machine_file(path);
  EXPECT_EQ(machine->model(), "toy_tripod");
  // Capabilities it does not declare are missing, and say so.
  EXPECT_EQ(machine->dynamics().reason(), "toy_tripod machines have no mass model");
  EXPECT_EQ(machine->translational_maps(), nullptr);
  const MachineDescription d = describe_machine_file(path);
  EXPECT_EQ(format_description(d),
            "model: toy_tripod\ndof: 3 (3 translations, 0 rotations)\ndrives: 0 serial, 3 "
            "parallel\nstructure_class: P0З3\nactuators: 3 prismatic\n");
  // A bad value is refused at its key, as for every model.
  EXPECT_THROW((void)load_machine_file(write("bad.yaml", "model: toy_tripod\nbase_radius: -1\n")),
               InputError);

  const PoseTable table =
      read_pose_csv(write("poses.csv",
                          "x,y,z,rx,ry,rz\n0,0,0.7,0,0,0\n0.1,-0.05,0.75,0,0,0\n"
                          "0,0,0.7,5,0,0\n"));
  const Wrench w = (Wrench() << 100, -50, -2000, 0, 0, 0).finished();
  const std::vector<PoseMetrics> metrics = analyze_poses(*machine, table.poses, w);
  ASSERT_EQ(metrics.size(), 3u);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_TRUE(metrics[k].reachable);
    // Independently: the leg lengths, and the legs' forces balance the force on the tool.
    Eigen::Vector3d balance = Eigen::Vector3d::Zero();
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d v = table.poses[k].position + joint(0.15, i) - joint(0.5, i);
      EXPECT_NEAR(metrics[k].q(i), v.norm(), 1e-15);
      balance += metrics[k].tau(i) * v.normalized();
    }
    EXPECT_NEAR((balance - w.head<3>()).norm(), 0.0, 1e-9);
  }
  EXPECT_FALSE(metrics[2].reachable);  // a level platform only
  const std::string csv = analyze_csv(*machine, table, metrics, {});
  EXPECT_EQ(csv.substr(0, csv.find(",tau_1")), "x,y,z,rx,ry,rz,reachable,q_1,q_2,q_3") << csv;
  EXPECT_NE(csv.find(format_number(metrics[1].q(0))), std::string::npos) << csv;
}

TEST_F(ToyModel, ForwardKinematicsReturnsThePoseOfItsLegLengths) {
  const std::unique_ptr<Machine> machine = load_machine_file(write("toy.yaml", file_));
  const Pose pose{{0.07, -0.04, 0.78}, {0, 0, 0}};
  PoseMetrics m;
  machine->analyze(*machine->make_data(), pose, Wrench::Zero(), m);
  const FkResult r = machine->forward_kinematics(m.q, std::nullopt);
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_LT((r.pose.position - pose.position).norm(), 1e-11);
  EXPECT_NE(fk_csv(r).find("converged"), std::string::npos) << fk_csv(r);
}

// The workspace is the part above the base of the intersection of three spherical shells
// (centres a_i - b_i, radii min_length..max_length): its volume by Monte Carlo, independently.
TEST_F(ToyModel, WorkspaceVolumeMatchesAMonteCarloEstimate) {
  const std::unique_ptr<Machine> machine = load_machine_file(write("toy.yaml", file_));
  WorkspaceOptions options;
  options.resolution = 0.02;
  options.compute_hull = false;
  options.compute_maps = false;
  const WorkspaceResult ws = compute_workspace(*machine, options);
  ASSERT_GT(ws.volume, 0.0);
  EXPECT_FALSE(ws.touches_search_box);
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> xy(-1.5, 1.5), z(0.0, 1.0);
  const int samples = 400000;
  int inside = 0;
  for (int s = 0; s < samples; ++s) {
    const Eigen::Vector3d p(xy(random), xy(random), z(random));
    bool in = true;
    for (int i = 0; i < 3 && in; ++i) {
      const double l = (p - (joint(0.5, i) - joint(0.15, i))).norm();
      in = l >= 0.6 && l <= 1.0;
    }
    inside += in ? 1 : 0;
  }
  const double box = 3.0 * 3.0 * 1.0;
  const double estimate = box * inside / samples;
  const double sigma = box * std::sqrt(double(inside) / samples / samples);
  std::cout << "toy workspace: grid " << ws.volume << " m^3, Monte Carlo " << estimate << " +- "
            << sigma << " m^3\n";
  EXPECT_NEAR(ws.volume, estimate, 4.0 * sigma + 0.01 * estimate)
      << "grid " << ws.volume << " m^3, Monte Carlo " << estimate << " +- " << sigma;
}

TEST_F(ToyModel, ADesignStudyRunsThroughItsFamilyAndWritesLoadableDesigns) {
  const std::string study = write("study.yaml", R"(study: toy
machine:
  model: toy_tripod
  parameters:
    base_radius: {min: 0.4, max: 0.6}
    stroke: {min: 0.3, max: 0.5}
  axial_stiffness: 2.0e7
task:
  region: {shape: box, centre: [0, 0, 0.7], size: [0.1, 0.1, 0.1], points: [2, 2, 2]}
  wrench: [0, 0, -500, 0, 0, 0]
objectives:
  - maximize: stiffness_min
  - minimize: machine_size
constraints:
  - task_reachable
optimizer: {algorithm: nsga2, population: 12, generations: 4, seed: 3}
)");
  // The study section's docs table comes from the family, as for the built-in models.
  EXPECT_NE(study_machine_fields_markdown("toy_tripod").find("| `stroke` |"), std::string::npos)
      << study_machine_fields_markdown("toy_tripod");
  const DesignStudy loaded = load_design_study(study);
  EXPECT_EQ(loaded.model, "toy_tripod");
  EXPECT_NE(loaded.resolved_yaml.find("  axial_stiffness: 20000000\n"), std::string::npos)
      << loaded.resolved_yaml;

  StudyRunOptions options;
  options.out = (dir_ / "out").string();
  options.threads = 2;
  options.show_progress = false;
  options.message = [](const std::string&) {};
  const StudyRunResult result = run_study_file(study, options);
  EXPECT_EQ(result.status, "ok");
  std::ifstream in(dir_ / "out" / "pareto.json");
  const nlohmann::json pareto = nlohmann::json::parse(in);
  EXPECT_EQ(pareto["model"], "toy_tripod");
  ASSERT_GT(pareto["designs"].size(), 0u);
  for (const auto& d : pareto["designs"]) {
    const std::unique_ptr<Machine> machine =
        load_machine_file((dir_ / "out" / d["machine_file"].get<std::string>()).string());
    auto data = machine->make_data();
    double worst = std::numeric_limits<double>::infinity();
    for (const Pose& task_pose : loaded.task().poses) {
      Pose pose = task_pose;
      pose.position.z() += d["home_height"].get<double>();
      PoseMetrics m;
      machine->analyze(*data, pose, loaded.task().wrench, m);
      EXPECT_TRUE(m.reachable);
      worst = std::min(worst, m.stiffness_min);
    }
    EXPECT_NEAR(worst / d["objectives"]["stiffness_min"].get<double>(), 1.0, 1e-12);
    const double r_b = d["parameters"]["base_radius"].get<double>();
    const double length = 0.6 + d["parameters"]["stroke"].get<double>();
    EXPECT_NEAR(d["objectives"]["machine_size"].get<double>(),
                std::numbers::pi * r_b * r_b * length, 1e-12);
  }
}

}  // namespace
}  // namespace pkmopt
