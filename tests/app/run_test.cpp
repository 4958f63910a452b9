// Tests of `pkmopt run` on benchmark studies: outputs, and strict study files.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace {

namespace fs = std::filesystem;

struct CommandResult {
  int status;
  std::string err;
};

CommandResult run_pkmopt(const std::string& args, const fs::path& work) {
  const fs::path err_file = work / "stderr.txt";
  const std::string command =
      std::string(PKMOPT_CLI) + " run " + args + " 2> " + err_file.string() + " > /dev/null";
  const int raw = std::system(command.c_str());
  std::ifstream in(err_file);
  std::stringstream text;
  text << in.rdbuf();
  return {WEXITSTATUS(raw), text.str()};
}

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("pkmopt_run_test_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(RunCommand, WritesFrontAndSummary) {
  const fs::path dir = fresh_dir("ok");
  std::ofstream(dir / "study.yaml")
      << "study: small\n"
         "problem: {benchmark: zdt1, variables: 5}\n"
         "optimizer: {algorithm: nsga2, population: 20, generations: 10, seed: 3}\n";
  const CommandResult r =
      run_pkmopt((dir / "study.yaml").string() + " --out " + (dir / "out").string(), dir);
  ASSERT_EQ(r.status, 0) << r.err;
  std::ifstream csv(dir / "out" / "pareto.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header, "x_1,x_2,x_3,x_4,x_5,f_1,f_2");
  std::ifstream summary_file(dir / "out" / "summary.json");
  std::stringstream summary;
  summary << summary_file.rdbuf();
  EXPECT_NE(summary.str().find("\"evaluations\": 220"), std::string::npos) << summary.str();
  EXPECT_NE(summary.str().find("\"hypervolume\""), std::string::npos);
  EXPECT_NE(summary.str().find("\"seed\": 3"), std::string::npos);
}

TEST(RunCommand, UnknownKeyIsAnErrorWithLocation) {
  const fs::path dir = fresh_dir("bad_key");
  std::ofstream(dir / "study.yaml") << "study: bad\n"
                                       "problem: {benchmark: zdt1}\n"
                                       "optimizer: {algorithm: nsga2, populaton: 20}\n";
  const CommandResult r =
      run_pkmopt((dir / "study.yaml").string() + " --out " + (dir / "out").string(), dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("study.yaml:3:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("populaton"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out" / "pareto.csv"));
}

TEST(RunCommand, UnsupportedAlgorithmIsAnError) {
  const fs::path dir = fresh_dir("unsupported");
  std::ofstream(dir / "study.yaml") << "study: bad\n"
                                       "problem: {benchmark: hs71}\n"
                                       "optimizer: {algorithm: \"nlopt:BOBYQA\"}\n";
  const CommandResult r =
      run_pkmopt((dir / "study.yaml").string() + " --out " + (dir / "out").string(), dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("equality constraints"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out" / "summary.json"));
}

TEST(RunCommand, UnknownBenchmarkIsAnError) {
  const fs::path dir = fresh_dir("unknown");
  std::ofstream(dir / "study.yaml") << "study: bad\n"
                                       "problem: {benchmark: zdt5}\n"
                                       "optimizer: {algorithm: nsga2}\n";
  const CommandResult r =
      run_pkmopt((dir / "study.yaml").string() + " --out " + (dir / "out").string(), dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("zdt5"), std::string::npos) << r.err;
}

}  // namespace
