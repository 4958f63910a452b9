#include "studies/run_folder.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <system_error>

#include "io/format/csv.hpp"
#include "io/format/input_error.hpp"
#include "io/format/output_file.hpp"

namespace pkmopt {

namespace fs = std::filesystem;

PreparedDirectory prepare_output_directory(const StudyRunOptions& opt) {
  const fs::path dir(opt.out);
  // A synthesis keeps one journal per candidate structure, in candidates/NAME/.
  const bool synthesis_run = fs::is_directory(dir / "candidates");
  const bool has_journal = fs::exists(dir / "journal.txt") || synthesis_run;
  const bool holds_run =
      has_journal || fs::exists(dir / "summary.json") || fs::exists(dir / "pareto.csv");
  if (!holds_run && fs::is_directory(dir)) {
    // A folder of something else (a home folder, a source tree) is never written into: --force
    // would remove files there. A folder a killed run left before its journal has its lock.
    std::error_code error;
    for (const fs::directory_entry& e : fs::directory_iterator(dir, error)) {
      const std::string name = e.path().filename().string();
      if (name == "run.lock" || name == "study.resolved.yaml" ||
          name.find(".tmp.") != std::string::npos)
        continue;
      throw InputError(fmt::format(
          "--out: expected a new or empty folder or a previous run, found the folder '{}' holding "
          "other files (such as {}); give another folder",
          opt.out, quote_found(name)));
    }
  }
  if (holds_run && !opt.resume && !opt.force)
    throw InputError(fmt::format(
        "--out: '{}' holds a previous run ({}); continue it with --resume or replace it with "
        "--force",
        opt.out,
        fs::exists(dir / "journal.txt") ? "journal.txt"
        : synthesis_run                 ? "candidates/"
                                        : "summary.json or pareto.csv"));
  std::error_code error;
  fs::create_directories(dir, error);
  if (error || !fs::is_directory(dir))
    throw InputError(fmt::format("--out: cannot create the folder '{}': {}", opt.out,
                                 error ? error.message() : "not a folder"));
  PreparedDirectory prepared;
  prepared.lock = std::make_unique<RunLock>(opt.out);
  if (opt.force) {
    for (const char* name :
         {"journal.txt", "evaluations.csv", "pareto.csv", "pareto.json", "summary.json",
          "study.resolved.yaml", "journal.damaged.txt", "candidates.csv", "candidates.json"})
      fs::remove(dir / name);
    fs::remove_all(dir / "candidates");
    if (fs::is_directory(dir / "designs"))
      for (const fs::directory_entry& e : fs::directory_iterator(dir / "designs"))
        if (e.path().extension() == ".yaml" && e.path().filename().string().starts_with("d"))
          fs::remove(e.path());
  }
  std::size_t stale = remove_stale_temporaries(opt.out);
  if (fs::is_directory(dir / "candidates"))
    for (const fs::directory_entry& e : fs::directory_iterator(dir / "candidates"))
      if (e.is_directory()) stale += remove_stale_temporaries(e.path().string());
  if (stale > 0)
    opt.message(fmt::format("removed {} temporary file{} left in '{}' by an interrupted run", stale,
                            stale == 1 ? "" : "s", opt.out));
  const bool journal_now =
      fs::exists(dir / "journal.txt") || fs::is_directory(dir / "candidates");
  if (opt.resume && !journal_now)
    opt.message(fmt::format("no journal in '{}': starting a new run", opt.out));
  prepared.resumed = opt.resume && journal_now;
  return prepared;
}

}  // namespace pkmopt
