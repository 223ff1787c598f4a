// Rigid sweep throughput: how many scenario runs of a rigid paper model (2 s horizon, 1 ms samples,
// exact stepping) one core, and both cores, complete per second. Each scenario scales the input
// torque and reduces its run to the peak magnitude of every output (velocities and mesh forces),
// as a design sweep would; the discretization is computed in every run, or once and reused.
#include <atomic>
#include <thread>

#include <pogear/simulate.hpp>

#include "paper_scenes.hpp"

namespace {

using namespace bench;

enum class Mode { per_run, reused, reused_states_only, lockstep8_states_only };

const char* mode_name(Mode m) {
  switch (m) {
    case Mode::per_run: return "discretization per run";
    case Mode::reused: return "discretization reused";
    case Mode::reused_states_only: return "reused - states only";
    default: return "lockstep x8 - states only (bench kernel)";
  }
}

// Not a pogear API: what stepping 8 scenarios in lockstep would give. One scenario's steps form a
// chain of dependent multiply-adds whose latency bounds the rate (~20 cycles per step for 2 states,
// whatever the driver does); 8 independent chains in one matrix product X <- Phi X + Gamma U fill
// the pipeline instead. Constant inputs (as the paper scenes'), states only, peak |omega| kept.
template <class Sys>
void run_lockstep8(const Problem<Sys>& pb, const rt::ExactDiscretization<Sys::nx, Sys::nu>& disc, long first,
                   long count, double* out) {
  using Block = Eigen::Matrix<double, Sys::nx, 8>;
  using Inputs = Eigen::Matrix<double, Sys::nu, 8>;
  typename Sys::Input u;
  pb.inputs(0, u);
  const typename Sys::InputMatrix gamma = disc.Gamma0;  // u0 = u1: Gamma0 u0 + Gamma1 (u1 - u0)
  for (long i = first; i < first + count; i += 8) {
    Inputs U;
    for (int j = 0; j < 8; ++j) U.col(j) = u * (0.5 + 0.01 * static_cast<double>((i + j) % 100));
    const Block drive = gamma * U;
    Block X = Block::Zero(), Xn, peak = Block::Zero();
    for (long k = 1; k < pb.count; ++k) {
      Xn.noalias() = disc.Phi * X;
      X = Xn + drive;
      peak = peak.cwiseMax(X.cwiseAbs());
    }
    for (int j = 0; j < 8; ++j) out[(i + j) % 1024] = peak.col(j).maxCoeff();
  }
}

// Runs scenarios [first, first + count) and writes each one's peaks into out.
template <class Sys>
void run_scenarios(const Problem<Sys>& pb, const rt::ExactDiscretization<Sys::nx, Sys::nu>& disc, Mode mode,
                   long first, long count, double* out) {
  using State = typename Sys::State;
  using Input = typename Sys::Input;
  rt::SolverOptions opt;
  opt.h = pb.dt;
  typename Sys::Output y, peak;
  Input u_run;
  State last;
  if (mode == Mode::lockstep8_states_only) return run_lockstep8(pb, disc, first, count, out);
  for (long i = first; i < first + count; ++i) {
    const double scale = 0.5 + 0.01 * static_cast<double>(i % 100);  // 50% ... 149% of the scene's torque
    pb.inputs(0, u_run);
    u_run *= scale;
    auto inputs = [&](double, Input& u) { u = u_run; };
    peak.setZero();
    auto obs = [&](double, const State& x) {
      if (mode == Mode::reused_states_only) {
        last = x;
        return;
      }
      Sys::outputs(pb.params, x, u_run, y);
      peak = peak.cwiseMax(y.cwiseAbs());
    };
    if (mode == Mode::per_run)
      rt::simulate_exact(pb.M, pb.N, inputs, pb.x0, 0.0, pb.horizon, pb.dt, opt, obs);
    else
      rt::simulate_exact(disc, pb.M, pb.N, inputs, pb.x0, 0.0, pb.horizon, pb.dt, opt, obs);
    out[i % 1024] = mode == Mode::reused_states_only ? last[0] : peak.maxCoeff();
  }
}

template <class Sys>
void bench_sweep(const Problem<Sys>& pb, const Options& o, Results& res, Checker& chk) {
  const rt::ExactDiscretization<Sys::nx, Sys::nu> disc(pb.M, pb.N, rt::exact_nominal_step(pb.dt, pb.dt));
  std::vector<double> out(2048, 0.0);
  // The sweep reproduces the scene at scale 1 (scenario 50): its peaks must match the reference's.
  {
    run_scenarios(pb, disc, Mode::reused, 50, 1, out.data());
    typename Sys::Output y, peak = Sys::Output::Zero();
    typename Sys::State x;
    typename Sys::Input u;
    pb.inputs(0, u);
    for (long k = 0; k < pb.count; ++k) {
      for (int i = 0; i < Sys::nx; ++i) x[i] = pb.ref.at(k, i);
      Sys::outputs(pb.params, x, u, y);
      peak = peak.cwiseMax(y.cwiseAbs());
    }
    chk.expect(std::abs(out[50] - peak.maxCoeff()) <= 1e-12 * peak.maxCoeff(),
               pb.label() + ": sweep scenario at scale 1 reproduces the scene's peak output");
  }
  const double min_batch = o.quick ? 0.02 : 0.3;
  // The lockstep kernel reproduces the reference too (states only: the peak |x| at scale 1).
  {
    run_scenarios(pb, disc, Mode::lockstep8_states_only, 48, 8, out.data());
    double peak = 0;
    for (long k = 0; k < pb.count; ++k)
      for (int i = 0; i < Sys::nx; ++i) peak = std::max(peak, std::abs(pb.ref.at(k, i)));
    chk.expect(std::abs(out[50] - peak) <= 1e-12 * peak, pb.label() + ": lockstep kernel reproduces the scene's peak state");
  }
  for (const Mode mode : {Mode::per_run, Mode::reused, Mode::reused_states_only, Mode::lockstep8_states_only}) {
    for (const int threads : {1, 2}) {
      // Calibrate on one thread: runs per batch such that a batch lasts >= min_batch.
      long n = 16;  // a multiple of 8 for the lockstep kernel
      for (;;) {
        const auto t0 = std::chrono::steady_clock::now();
        run_scenarios(pb, disc, mode, 0, n, out.data());
        if (seconds_since(t0) >= min_batch / 4 || n > (1L << 26)) break;
        n *= 2;
      }
      n *= 4;
      std::vector<double> rates;
      for (int b = 0; b < o.batches; ++b) {
        const auto t0 = std::chrono::steady_clock::now();
        if (threads == 1) {
          run_scenarios(pb, disc, mode, 0, n, out.data());
        } else {  // each thread its own scenarios and output slots, no sharing in the loop
          std::thread t([&] { run_scenarios(pb, disc, mode, 0, n, out.data()); });
          run_scenarios(pb, disc, mode, n, n, out.data() + 1024);
          t.join();
        }
        rates.push_back(static_cast<double>(n * threads) / seconds_since(t0));
      }
      std::sort(rates.begin(), rates.end());
      const double med = rates[rates.size() / 2];
      res.line(pb.scene + "," + pb.model + "," + std::to_string(Sys::nx) + "," + fmt_double(pb.horizon) + "," +
               mode_name(mode) + "," + std::to_string(threads) + "," + fmt_double(med) + "," +
               fmt_double(rates.front()) + "," + fmt_double(rates.back()) + "," + std::to_string(n * threads));
      std::printf("  %-24s %-24s %d thread%s: %s runs/s (min %s, max %s)\n", pb.label().c_str(), mode_name(mode),
                  threads, threads > 1 ? "s" : " ", fmt_double(med).c_str(), fmt_double(rates.front()).c_str(),
                  fmt_double(rates.back()).c_str());
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse_options(argc, argv);
  Checker chk;
  chk.enabled = o.check;
  Results res(o.out + "/sweep.csv", "scene,model,nx,horizon_s,mode,threads,runs_per_s_median,runs_per_s_min,"
                                    "runs_per_s_max,runs_per_batch");
  std::printf("rigid sweep (2 s horizon, 1 ms samples, exact stepping; %u hardware threads)\n",
              std::thread::hardware_concurrency());
  for_each_paper_scene([&](const auto&, const auto& rigid) {
    // The sweep horizon is 2 s for both scenes (the two-stage scene itself runs 1 s).
    auto pb = rigid;
    pb.horizon = 2.0;
    pb.count = std::lround(pb.horizon / pb.dt) + 1;
    pb.ref = exact_reference(pb);
    bench_sweep(pb, o, res, chk);
  });
  return chk.exit_code("sweep");
}
