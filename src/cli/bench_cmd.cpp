// `zsweep bench scan MESH... --sizes ... --strategies ... [--variants ...]
//  --csv OUT.csv [--plots DIR] [--repeat N]`
#include <charconv>
#include <cstdio>
#include <memory>
#include <sstream>

#include <CLI/CLI.hpp>

#include "app/option_checks.h"
#include "bench/accuracy_bench.h"
#include "bench/bench_inputs.h"
#include "bench/scan_bench.h"
#include "cli/commands.h"

namespace zs {

namespace {

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

std::vector<uint32_t> parse_sizes(const std::string& list) {
  std::vector<uint32_t> sizes;
  for (const auto& s : split(list)) {
    long v = 0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || end != s.data() + s.size() || v < 1 || v > 65536) throw std::runtime_error("--sizes: " + s + " is not an image size");
    sizes.push_back(uint32_t(v));
  }
  return sizes;
}

}  // namespace

void add_bench_report_command(CLI::App& bench);
void add_bench_accuracy_command(CLI::App& bench);

void add_bench_command(CLI::App& app) {
  CLI::App* bench = app.add_subcommand("bench", "Benchmarks (CSV + PNG plots)");
  bench->require_subcommand(1);
  struct Args {
    std::vector<std::string> inputs;
    std::string sizes = "512,1024,2048", strategies = "bbox,bconvert,span", variants = "truncate";
    std::string csv, plots;
    int repeat = 1;
    double memory_budget_mb = 0;
    uint32_t raster_only_above = 8192;
  };
  auto a = std::make_shared<Args>();
  CLI::App* scan = bench->add_subcommand("scan", "Scan-convert strategies: the seed's B-Convert experiment");
  scan->add_option("inputs", a->inputs, "Volume scene .json files or tet meshes (camera: rotation 0, mesh filling the image). "
                 "Rows are named by the file's stem; inputs sharing a stem by their file names "
                 "(spx.json, spx.off), the same name twice with -2, -3 on the later ones")
      ->required();
  scan->add_option("--sizes", a->sizes, "Comma-separated image sizes")->capture_default_str();
  scan->add_option("--strategies", a->strategies, "bbox,bconvert,span")->capture_default_str();
  scan->add_option("--variants", a->variants, "B-Convert variants: truncate,round,dilate,dda3d,runlength")
      ->capture_default_str();
  scan->add_option("--csv", a->csv, "Output CSV")->required();
  scan->add_option("--plots", a->plots, "Directory for PNG plots and tables.md");
  scan->add_option("--repeat", a->repeat, "Runs per case; the fastest counts")->check(number_check(whole_range(1, 100)));
  scan->add_option("--raster-only-above", a->raster_only_above,
                   "Sizes above this skip compositing (counts and scan times only)")
      ->capture_default_str();
  scan->add_option("--memory-budget", a->memory_budget_mb, "MiB (default: half of physical memory)")
      ->check(number_check(positive_range(1.7e13)));
  scan->callback([a] {
    ScanBenchOptions o;
    o.inputs = a->inputs;
    o.sizes = parse_sizes(a->sizes);
    o.strategies.clear();
    for (const auto& s : split(a->strategies)) {
      ScanStrategy k;
      if (!parse_scan_strategy(s, &k)) throw std::runtime_error("--strategies: unknown strategy '" + s + "'");
      o.strategies.push_back(k);
    }
    o.variants.clear();
    for (const auto& s : split(a->variants)) {
      BConvertVariant v;
      if (!parse_bconvert_variant(s, &v)) throw std::runtime_error("--variants: unknown variant '" + s + "'");
      o.variants.push_back(v);
    }
    o.csv = a->csv;
    o.plots_dir = a->plots;
    o.repeat = a->repeat;
    o.raster_only_above = a->raster_only_above;
    o.memory_budget_bytes = uint64_t(a->memory_budget_mb * 1048576.0);
    check_bench_outputs(o.csv, o.plots_dir);  // not after minutes of measuring
    const auto rows = run_scan_bench(o);
    write_scan_bench_csv(o.csv, rows);
    if (!o.plots_dir.empty()) write_scan_bench_report(o.plots_dir, rows);
    std::printf("wrote %s (%zu rows)%s%s\n", o.csv.c_str(), rows.size(), o.plots_dir.empty() ? "" : ", plots in ",
                o.plots_dir.c_str());
  });
  add_bench_report_command(*bench);
  add_bench_accuracy_command(*bench);
}

void add_bench_accuracy_command(CLI::App& bench) {
  struct Args {
    std::vector<std::string> inputs;
    std::string sizes = "512", groups = "integrator,scan,early-termination,max-list,resolution";
    std::string csv, plots;
    int repeat = 1, threads = 1;
  };
  auto a = std::make_shared<Args>();
  CLI::App* acc = bench.add_subcommand("accuracy", "Speed vs accuracy: every ZSweep setting against the reference");
  acc->add_option("inputs", a->inputs, "Volume scene .json files, tet meshes, or 'default' (the embedded scene). "
                 "Rows are named as in bench scan: the stem, or the file name where two share a stem")->required();
  acc->add_option("--sizes", a->sizes, "Comma-separated image sizes")->capture_default_str();
  acc->add_option("--groups", a->groups, "Axes to measure")->capture_default_str();
  acc->add_option("--csv", a->csv, "Output CSV")->required();
  acc->add_option("--plots", a->plots, "Directory for the PNG figures");
  acc->add_option("--repeat", a->repeat, "Runs per setting; the fastest counts")->check(number_check(whole_range(1, 100)));
  acc->add_option("--threads", a->threads, "Threads for every render (and the reference)")->check(number_check(whole_range(1, 1024)));
  acc->callback([a] {
    AccuracyBenchOptions o;
    o.inputs = a->inputs;
    o.sizes = parse_sizes(a->sizes);
    o.groups = split(a->groups);
    for (const auto& g : o.groups)
      if (g != "integrator" && g != "scan" && g != "early-termination" && g != "max-list" && g != "resolution")
        throw std::runtime_error("--groups: unknown axis '" + g + "'");
    o.csv = a->csv;
    o.plots_dir = a->plots;
    o.repeat = a->repeat;
    o.threads = a->threads;
    check_bench_outputs(o.csv, o.plots_dir);  // not after minutes of measuring
    const auto rows = run_accuracy_bench(o);
    write_accuracy_csv(o.csv, rows);
    if (!o.plots_dir.empty()) write_accuracy_plots(o.plots_dir, rows);
    std::printf("wrote %s (%zu rows)%s%s\n", o.csv.c_str(), rows.size(), o.plots_dir.empty() ? "" : ", plots in ",
                o.plots_dir.c_str());
  });
}

void add_bench_report_command(CLI::App& bench) {
  struct Args {
    std::vector<std::string> csvs;
    std::string plots;
  };
  auto a = std::make_shared<Args>();
  CLI::App* rep = bench.add_subcommand("report", "Merge bench scan CSVs into one set of tables and plots");
  rep->add_option("csvs", a->csvs, "CSV files written by `zsweep bench scan`")->required();
  rep->add_option("--plots", a->plots, "Output directory for tables.md and PNG plots")->required();
  rep->callback([a] {
    check_bench_outputs("", a->plots);
    std::vector<ScanBenchRow> rows;
    for (const auto& c : a->csvs) {
      auto r = read_scan_bench_csv(c);
      rows.insert(rows.end(), r.begin(), r.end());
    }
    write_scan_bench_report(a->plots, rows);
    std::printf("wrote %s/tables.md and plots (%zu rows)\n", a->plots.c_str(), rows.size());
  });
}

}  // namespace zs
