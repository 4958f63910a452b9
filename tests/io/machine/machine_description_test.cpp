// Tests of io/machine/machine_description and `pkmopt describe`: degrees of freedom and the seeds'
// structure classes (P5З0 traditional, P0З6 pure parallel, P1З6 hybrid), and bad files.
#include "io/machine/machine_description.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "io/format/input_error.hpp"
#include "tests/cli_runner.hpp"
#include "tests/scratch_dir.hpp"

namespace pkmopt {
namespace {

const std::string kExamples = std::string(PKMOPT_SOURCE_DIR) + "/examples/";

class MachineDescriptionTest : public scratch::ScratchDirTest {
 protected:
  std::string error_of(const std::string& text) {
    try {
      describe_machine_file(write("m.yaml", text));
    } catch (const InputError& e) {
      return std::string(e.what()).substr(dir_.string().size() + 1);
    }
    return "no error";
  }
};

TEST_F(MachineDescriptionTest, FiveAxisSerialMachineIsP5Z0) {
  const MachineDescription d = describe_machine_file(kExamples + "serial_641236.yaml");
  EXPECT_EQ(d.translations, 3);
  EXPECT_EQ(d.rotations, 2);  // C and A; the spindle is the cutting motion, not a feed
  EXPECT_EQ(d.serial_drives, 5);
  EXPECT_EQ(d.parallel_drives, 0);
  EXPECT_EQ(d.structure, "P5З0");
  EXPECT_EQ(format_description(d),
            "model: serial\nname: 5-axis milling machine 641236\n"
            "dof: 5 (3 translations, 2 rotations)\ndrives: 5 serial, 0 parallel\n"
            "structure_class: P5З0\ncode: 641236\n"
            "axes: C(6) A(4) X(1) Y(2) Z(3) S(6, spindle)\n");
}

TEST_F(MachineDescriptionTest, HexapodIsP0Z6AndLongAxisHexapodIsP1Z6) {
  const MachineDescription hexapod = describe_machine_file(kExamples + "hexapod.yaml");
  EXPECT_EQ(hexapod.structure, "P0З6");
  EXPECT_EQ(hexapod.translations + hexapod.rotations, 6);
  const MachineDescription hybrid =
      describe_machine_file(kExamples + "hybrid_long_axis_hexapod.yaml");
  EXPECT_EQ(hybrid.structure, "P1З6");
  EXPECT_EQ(hybrid.translations, 4);
  EXPECT_EQ(hybrid.rotations, 3);
  EXPECT_NE(format_description(hybrid).find("dof: 7 (4 translations, 3 rotations), redundant"),
            std::string::npos);
}

// Every file that analyze reads is described: a hybrid with axis masses and gravity too.
TEST_F(MachineDescriptionTest, HybridWithMassesIsDescribed) {
  const MachineDescription hybrid =
      describe_machine_file(kExamples + "hybrid_long_axis_masses.yaml");
  EXPECT_EQ(hybrid.structure, "P1З6");
}

// describe_machine on a parsed document describes it as its file; a hybrid's module file is
// taken from the folder of the document's file.
TEST_F(MachineDescriptionTest, ParsedDocumentIsDescribedAsItsFile) {
  for (const char* name : {"serial_641236.yaml", "hybrid_long_axis_hexapod.yaml"}) {
    const std::string file = kExamples + name;
    EXPECT_EQ(format_description(describe_machine(YamlValue::load_file(file))),
              format_description(describe_machine_file(file)))
        << name;
  }
  const YamlValue moved = YamlValue::load_string(
      read_input_file(kExamples + "hybrid_long_axis_hexapod.yaml"), path("elsewhere.yaml"));
  EXPECT_THROW(describe_machine(moved), InputError);  // its module file is not in dir_
}

TEST_F(MachineDescriptionTest, TripodLatheAndSchoenfliesMobilities) {
  const MachineDescription tripod = describe_machine_file(kExamples + "tripod_3prs.yaml");
  EXPECT_EQ(tripod.translations, 1);  // z; x, y and rz are parasitic
  EXPECT_EQ(tripod.rotations, 2);
  EXPECT_EQ(tripod.structure, "P0З3");
  const MachineDescription schoenflies = describe_machine_file(kExamples + "schoenflies_4pus.yaml");
  EXPECT_EQ(schoenflies.translations, 3);
  EXPECT_EQ(schoenflies.rotations, 1);
  EXPECT_EQ(schoenflies.structure, "P0З4");
  const MachineDescription lathe = describe_machine_file(
      std::string(PKMOPT_SOURCE_DIR) + "/studies/library/lathe-16k20f3/lathe.yaml");
  EXPECT_EQ(lathe.translations, 3);  // the turret: x, y, z and the turn about the spindle axis
  EXPECT_EQ(lathe.rotations, 1);
  EXPECT_EQ(lathe.parallel_drives, 4);
  EXPECT_EQ(lathe.structure, "P0З4");
}

TEST_F(MachineDescriptionTest, GantryOverAParallelHeadCountsBoth) {
  std::filesystem::copy_file(kExamples + "hexapod.yaml", dir_ / "head.yaml");
  const MachineDescription d =
      describe_machine_file(write("g.yaml",
                                  "model: hybrid\nserial: {code: \"12\", axes: [X, Y], "
                                  "range: [[-1, 1], [-0.5, 0.5]]}\n"
                                  "parallel: {file: head.yaml, home: [0, 0, 0.9]}\n"));
  EXPECT_EQ(d.structure, "P2З6");
  EXPECT_EQ(d.serial_drives, 2);
}

TEST_F(MachineDescriptionTest, BadFilesNameTheKey) {
  EXPECT_EQ(error_of("model: serial\ncode: \"64x\"\n"),
            "m.yaml:2:7: code: coordinate code '64x': expected a motion digit 1..6 at position "
            "3, found 'x'");
  EXPECT_EQ(error_of("model: serial\ncode: \"123\"\naxes: [X, Y]\n"),
            "m.yaml:3:7: axes: expected a list of 3, found a list of 2");
  EXPECT_EQ(error_of("model: serial\ncode: \"123\"\naxes: [X, Y, X]\n"),
            "m.yaml:3:7: axes: expected distinct axis names, found a list of 3");
  EXPECT_EQ(error_of("model: serial\ncode: \"1236\"\naxes: [X, Y, Z, S]\nspindle: Z\n"),
            "m.yaml:4:10: spindle: expected a rotary axis (motion 4, 5 or 6), found 'Z'");
  EXPECT_EQ(error_of("model: hybrid\nserial: {code: \"1\", range: [[-1, 1]]}\n"
                     "parallel: {file: none.yaml, home: [0, 0, 0.9]}\n"),
            "m.yaml:3:18: parallel.file: expected an existing machine file, found '" +
                (dir_ / "none.yaml").string() + "' (no such file)");
  // The serial numbers are read as analyze reads them (a range is required there too).
  EXPECT_EQ(error_of("model: hybrid\nserial: {code: \"1\"}\nparallel: {file: none.yaml}\n"),
            "m.yaml:2:9: serial: missing required key 'range'");
}

TEST_F(MachineDescriptionTest, CliPrintsTheDescriptionAndRejectsBadFiles) {
  cli_runner::CliRun run = run_cli("describe " + kExamples + "serial_641236.yaml");
  EXPECT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("structure_class: P5З0"), std::string::npos);
  run = run_cli("describe " + write("bad.yaml", "model: serial\n"));
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.err.find("missing required key 'code'"), std::string::npos) << run.err;
}

}  // namespace
}  // namespace pkmopt
