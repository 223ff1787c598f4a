// What writing the samples costs, split into its parts: the outputs of every sample of the paper
// scenes' exact runs are written with the runtime's CsvWriter (as the generated main writes them)
// to a memory file system (/dev/shm: number formatting and copying only) and to the results
// directory (the same, plus the file system: replacing the file, and as a new file), and read back
// to check the numbers round-trip.
#include <charconv>

#include <pogear/csv.hpp>
#include <pogear/exact.hpp>
#include <pogear/drivers.hpp>

#include "paper_scenes.hpp"

namespace {

using namespace bench;

struct Table {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;  // t, then the outputs
};

// Every sample's outputs, computed as the generated main computes them.
template <class Sys>
Table sampled_outputs(const Problem<Sys>& pb) {
  Table tab{{"t [s]"}, {}};
  for (std::size_t i = 0; i < std::size(Sys::output_names); ++i)
    tab.columns.push_back(std::string(Sys::output_names[i]) + " [" + std::string(Sys::output_units[i]) + "]");
  typename Sys::Input u;
  typename Sys::Output y;
  rt::SolverOptions opt;
  opt.h = pb.dt;
  auto inputs = [&](double t, typename Sys::Input& v) { pb.inputs(t, v); };
  auto obs = [&](double t, const typename Sys::State& x) {
    pb.inputs(t, u);
    Sys::outputs(pb.params, x, u, y);
    std::vector<double> row{t};
    for (int i = 0; i < Sys::ny; ++i) row.push_back(y[i]);
    tab.rows.push_back(std::move(row));
  };
  rt::simulate_exact(pb.M, pb.N, inputs, pb.x0, 0.0, pb.horizon, pb.dt, opt, obs, {});
  return tab;
}

bool write_csv(const Table& tab, const std::string& path) {
  rt::CsvWriter w(path, tab.columns);
  if (!w.ok()) return false;
  for (const auto& row : tab.rows) {
    for (double v : row) w.field(v);
    w.end_row();
  }
  return w.commit();
}

// The file read back: every number equals the one written (shortest round-trip form).
bool round_trips(const Table& tab, const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);  // header
  for (const auto& row : tab.rows) {
    if (!std::getline(in, line)) return false;
    const char* p = line.data();
    const char* end = p + line.size();
    for (std::size_t i = 0; i < row.size(); ++i) {
      double v = 0;
      const auto r = std::from_chars(p, end, v);
      if (r.ec != std::errc() || v != row[i]) return false;
      p = r.ptr + (r.ptr < end ? 1 : 0);
    }
  }
  return !std::getline(in, line);
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse_options(argc, argv);
  Checker chk{o.check};
  Results res(o.out + "/csv_cost.csv",
              "scene,model,where,rows,numbers,bytes,time_median,time_min,time_max,ns_per_number");
  const std::string disk_dir = o.out + "/csv_cost";
  std::filesystem::create_directories(disk_dir);
  std::string memory_dir;
  if (std::error_code ec; std::filesystem::is_directory("/dev/shm", ec)) {
    memory_dir = "/dev/shm/pogear_bench_csv_" + std::to_string(::getpid());
    std::filesystem::create_directories(memory_dir, ec);
    if (ec) memory_dir.clear();
  }
  if (memory_dir.empty()) std::printf("note: no writable /dev/shm; the memory-only row is skipped\n");

  auto measure_system = [&](const auto& pb) {
    const Table tab = sampled_outputs(pb);
    std::size_t numbers = 0;
    for (const auto& row : tab.rows) numbers += row.size();
    // disk_new removes the file before each write (inside the timing): ext4 writes the data of a
    // file that replaces another by rename out at once (auto_da_alloc), a new file it does not.
    for (const auto& [where, dir] : {std::pair{std::string("memory"), memory_dir}, std::pair{std::string("disk"), disk_dir},
                                     std::pair{std::string("disk_new"), disk_dir}}) {
      if (dir.empty()) continue;
      const std::string path = dir + "/" + pb.scene + "." + pb.model + ".csv";
      const bool remove_first = where == "disk_new";
      bool ok = true;
      const Timing tm = measure(
          [&] {
            if (remove_first) std::remove(path.c_str());
            ok = write_csv(tab, path) && ok;
          },
          o);
      chk.expect(ok, pb.label() + ": CSV written to " + where);
      chk.expect(round_trips(tab, path), pb.label() + ": every number of the CSV (" + where + ") reads back equal");
      const auto bytes = std::filesystem::file_size(path);
      res.line(pb.scene + "," + pb.model + "," + where + "," + std::to_string(tab.rows.size()) + "," +
               std::to_string(numbers) + "," + std::to_string(bytes) + "," + fmt_double(tm.median) + "," +
               fmt_double(tm.min) + "," + fmt_double(tm.max) + "," +
               fmt_double(tm.median / static_cast<double>(numbers) * 1e9));
      std::printf("  %-22s %-6s %zu numbers, %ju bytes: %s s per file, %s ns per number\n", pb.label().c_str(),
                  where.c_str(), numbers, static_cast<std::uintmax_t>(bytes), fmt_double(tm.median).c_str(),
                  fmt_double(tm.median / static_cast<double>(numbers) * 1e9).c_str());
    }
  };
  for_each_paper_scene([&](const auto& elastic, const auto& rigid) {
    measure_system(elastic);
    measure_system(rigid);
  });
  if (!memory_dir.empty()) std::filesystem::remove_all(memory_dir);
  return chk.exit_code("bench_csv_cost");
}
