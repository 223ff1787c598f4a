// Rigid sweep throughput: how many scenario runs of a rigid paper model (2 s horizon, 1 ms samples,
// exact stepping) one core, and both cores, complete per second. Each scenario scales the input
// torque and reduces its run to the peak magnitude of every output (velocities and mesh forces),
// as a design sweep would: one run at a time (simulate_exact, the discretization computed in every
// run or reused), or 8 in lockstep (simulate_exact_batch, outputs batched too).
#include <thread>

#include <pogear/sweep.hpp>

#include "paper_scenes.hpp"

namespace {

using namespace bench;

enum class Mode { per_run, reused, reused_states_only, batch_states_only, batch, batch_peaks };

const char* mode_name(Mode m) {
  switch (m) {
    case Mode::per_run: return "discretization per run";
    case Mode::reused: return "discretization reused";
    case Mode::reused_states_only: return "reused - states only";
    case Mode::batch_states_only: return "batch x8 - states only";
    case Mode::batch: return "batch x8 - outputs to observer";
    default: return "batch x8 - sweep_exact_peaks";
  }
}

constexpr int kBatch = 8;
double scale_of(long i) { return 0.5 + 0.01 * static_cast<double>(i % 100); }  // 50% ... 149% of the torque

// Scenarios [first, first + count) in batches of kBatch (count a multiple of it): each one's peak
// |output| (or peak |state|, states only) into out. The inputs are constant per scenario.
template <class Sys>
void run_batches(const Problem<Sys>& pb, const rt::ExactDiscretization<Sys::nx, Sys::nu>& disc,
                 const rt::LinearOutputs<Sys::ny, Sys::nx, Sys::nu>& lo, Mode mode, long first, long count,
                 double* out) {
  rt::SolverOptions opt;
  opt.h = pb.dt;
  typename Sys::Input u;
  pb.inputs(0, u);
  rt::BatchState<Sys::nx, kBatch> X0;
  for (int s = 0; s < kBatch; ++s) X0.col(s) = pb.x0;
  for (long i = first; i < first + count; i += kBatch) {
    rt::BatchInput<Sys::nu, kBatch> U;
    for (int s = 0; s < kBatch; ++s) U.col(s) = u * scale_of(i + s);
    auto inputs = [&](double, rt::BatchInput<Sys::nu, kBatch>& Us) { Us = U; };
    if (mode == Mode::batch_peaks) {
      rt::BatchOutput<Sys::ny, kBatch> peak = rt::BatchOutput<Sys::ny, kBatch>::Zero();
      rt::sweep_exact_peaks(disc, pb.M, pb.N, lo, inputs, X0, 0.0, pb.horizon, pb.dt, opt, peak);
      for (int s = 0; s < kBatch; ++s) out[(i + s) % 1024] = peak.col(s).maxCoeff();
    } else if (mode == Mode::batch) {
      rt::BatchOutput<Sys::ny, kBatch> peak = rt::BatchOutput<Sys::ny, kBatch>::Zero();
      rt::simulate_exact_batch(disc, pb.M, pb.N, lo, inputs, X0, 0.0, pb.horizon, pb.dt, opt,
                               [&](double, const rt::BatchState<Sys::nx, kBatch>&,
                                   const rt::BatchOutput<Sys::ny, kBatch>& Y) { rt::update_peaks(Y, peak); });
      for (int s = 0; s < kBatch; ++s) out[(i + s) % 1024] = peak.col(s).maxCoeff();
    } else {
      rt::BatchState<Sys::nx, kBatch> peak = rt::BatchState<Sys::nx, kBatch>::Zero();
      rt::simulate_exact_batch(disc, pb.M, pb.N, inputs, X0, 0.0, pb.horizon, pb.dt, opt,
                               [&](double, const rt::BatchState<Sys::nx, kBatch>& X) { peak = peak.cwiseMax(X.cwiseAbs()); });
      for (int s = 0; s < kBatch; ++s) out[(i + s) % 1024] = peak.col(s).maxCoeff();
    }
  }
}

// Runs scenarios [first, first + count) and writes each one's peaks into out.
template <class Sys>
void run_scenarios(const Problem<Sys>& pb, const rt::ExactDiscretization<Sys::nx, Sys::nu>& disc,
                   const rt::LinearOutputs<Sys::ny, Sys::nx, Sys::nu>& lo, Mode mode, long first, long count,
                   double* out) {
  using State = typename Sys::State;
  using Input = typename Sys::Input;
  if (mode == Mode::batch_states_only || mode == Mode::batch || mode == Mode::batch_peaks)
    return run_batches(pb, disc, lo, mode, first, count, out);
  rt::SolverOptions opt;
  opt.h = pb.dt;
  typename Sys::Output y, peak;
  Input u_run;
  State last;
  for (long i = first; i < first + count; ++i) {
    pb.inputs(0, u_run);
    u_run *= scale_of(i);
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
  const auto lo = rt::linear_outputs(Sys{}, pb.params);
  std::vector<double> out(2048, 0.0);
  // The sweep reproduces the scene at scale 1 (scenario 50): its peaks must match the reference's.
  // One run at a time calls the generated outputs; the batch computes C x + D u, which groups the
  // terms differently: both to rounding of the reference (1e-12 relative).
  {
    typename Sys::Output y, peak = Sys::Output::Zero();
    typename Sys::State x;
    typename Sys::Input u;
    pb.inputs(0, u);
    double peak_x = 0;
    for (long k = 0; k < pb.count; ++k) {
      for (int i = 0; i < Sys::nx; ++i) x[i] = pb.ref.at(k, i), peak_x = std::max(peak_x, std::abs(x[i]));
      Sys::outputs(pb.params, x, u, y);
      peak = peak.cwiseMax(y.cwiseAbs());
    }
    run_scenarios(pb, disc, lo, Mode::reused, 50, 1, out.data());
    chk.expect(std::abs(out[50] - peak.maxCoeff()) <= 1e-12 * peak.maxCoeff(),
               pb.label() + ": sweep scenario at scale 1 reproduces the scene's peak output");
    for (const Mode m : {Mode::batch, Mode::batch_peaks}) {
      run_scenarios(pb, disc, lo, m, 48, kBatch, out.data());
      chk.expect(std::abs(out[50] - peak.maxCoeff()) <= 1e-12 * peak.maxCoeff(),
                 pb.label() + ": " + mode_name(m) + ": scenario at scale 1 reproduces the scene's peak output");
    }
    run_scenarios(pb, disc, lo, Mode::batch_states_only, 48, kBatch, out.data());
    chk.expect(std::abs(out[50] - peak_x) <= 1e-12 * peak_x,
               pb.label() + ": batch scenario at scale 1 reproduces the scene's peak state");
  }
  const double min_batch = o.quick ? 0.02 : 0.3;
  for (const Mode mode : {Mode::per_run, Mode::reused, Mode::reused_states_only, Mode::batch_states_only, Mode::batch,
                          Mode::batch_peaks}) {
    for (const int threads : {1, 2}) {
      // Calibrate on one thread: runs per batch such that a batch lasts >= min_batch.
      long n = 16;  // a multiple of the batch size
      for (;;) {
        const auto t0 = std::chrono::steady_clock::now();
        run_scenarios(pb, disc, lo, mode, 0, n, out.data());
        if (seconds_since(t0) >= min_batch / 4 || n > (1L << 26)) break;
        n *= 2;
      }
      n *= 4;
      std::vector<double> rates;
      for (int b = 0; b < o.batches; ++b) {
        const auto t0 = std::chrono::steady_clock::now();
        if (threads == 1) {
          run_scenarios(pb, disc, lo, mode, 0, n, out.data());
        } else {  // each thread its own scenarios and output slots, no sharing in the loop
          std::thread t([&] { run_scenarios(pb, disc, lo, mode, 0, n, out.data()); });
          run_scenarios(pb, disc, lo, mode, n, n, out.data() + 1024);
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
