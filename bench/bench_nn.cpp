// Neural-network training speed on the Python peer's problem (bench/run_nn.sh runs the peer
// beside it): the peer's data, starting weights and fixed scaling z_v = v/0.1, z_a = a/0.6,
// unscaled output, so both sides solve the identical least-squares problem.
//
//   bench_nn --case v  --data p2_data_v.csv  --init p2_init_v.csv  [--best 0.0025549]
//   bench_nn --case va --data p2_data_va.csv --init p2_init_va.csv [--epochs 5]
//   bench_nn --case sweep --data p2_data_v.csv [--threads T]
//   bench_nn --case epoch --data p2_data_va.csv --init p2_init_va.csv [--threads T]
//     one LM epoch (normal equations, Cholesky, trial forward pass) by the old kernels
//     (legacy_mlp_kernels.hpp: default flags, one thread), the generic and the best SIMD
//     kernels on 1 thread and on T threads (default: all cores); GFLOP/s of J'J + J'r; the
//     largest relative difference to the old kernels.
//   bench_nn --case kernels --data p2_data_v.csv --init p2_init_v.csv [--repeats 31]
//     each kernel entry point on one thread (best instruction set), minimum and median time:
//     sum of squares, normal equations, output-layer solve, residuals, Jacobian. For
//     before/after comparisons of a kernel change (two builds, runs interleaved).
// Prints one JSON object per line.
#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "legacy_mlp_kernels.hpp"
#include "nn/mlp_kernels.hpp"
#include "sysid/io.hpp"
#include "sysid/nn.hpp"

namespace {

using Clock = std::chrono::steady_clock;
double Seconds(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Median wall time of `repeats` calls of f.
double Median(int repeats, const std::function<void()>& f) {
  std::vector<double> t;
  for (int i = 0; i < repeats; ++i) {
    const auto t0 = Clock::now();
    f();
    t.push_back(Seconds(t0));
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

Eigen::VectorXd ReadTheta(const std::string& path) {
  std::istringstream in(sysid::ReadFile(path));
  std::vector<double> v;
  for (std::string line; std::getline(in, line);)
    if (!line.empty() && line[0] != '#') v.push_back(std::stod(line));
  return Eigen::Map<Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

struct Args {
  std::string which = "v", data, init;
  double best = 0.0025549;  // the peer README's best known MSE for case v
  int epochs = 5, repeats = 5, threads = 0;
};

sysid::NeuralTrainingOptions PeerProblem(const std::vector<std::string>& inputs) {
  sysid::NeuralTrainingOptions o;
  for (const auto& name : inputs)
    o.input_ranges.push_back(name == "a" ? std::pair{-0.6, 0.6} : std::pair{-0.1, 0.1});
  o.output_range = std::pair{-1.0, 1.0};  // y in volts, unscaled, as in the peer
  o.gradient_tolerance = 0;
  return o;
}

// Minimum wall time of `repeats` calls of f (the least disturbed by other load).
double Minimum(int repeats, const std::function<void()>& f) {
  double best = 1e300;
  for (int i = 0; i < repeats; ++i) {
    const auto t0 = Clock::now();
    f();
    best = std::min(best, Seconds(t0));
  }
  return best;
}

// Each kernel entry point on one thread; see the file comment.
void KernelTimes(const sysid::NeuralDataset& d, const Eigen::VectorXd& theta, int H,
                 int repeats) {
  const int n = static_cast<int>(d.inputs.cols());
  Eigen::MatrixXd Z = d.inputs.transpose();
  for (int i = 0; i < n; ++i) Z.row(i) /= d.input_names[i] == "a" ? 0.6 : 0.1;
  const Eigen::VectorXd& y = d.targets;
  Eigen::MatrixXd JtJ, J, A;
  Eigen::VectorXd g, r, t = theta;
  double sse = 0;
  const std::vector<std::pair<const char*, std::function<void()>>> kernels = {
      {"sum_squares", [&] { sse = sysid::internal::nn::SumSquares(Z, y, H, theta); }},
      {"normal_equations", [&] { sysid::internal::nn::NormalEquations(Z, y, H, theta, &JtJ, &g, &sse); }},
      {"solve_output_layer", [&] { sse = sysid::internal::nn::SolveOutputLayer(Z, y, H, &t, &A); }},
      {"residuals", [&] { sysid::internal::nn::Residuals(Z, y, H, theta, &r); }},
      {"jacobian", [&] { sysid::internal::nn::Jacobian(Z, y, H, theta, &J); }}};
  nlohmann::ordered_json j{{"what", "kernel_times"}, {"isa", sysid::internal::nn::KernelIsa()},
                           {"N", Z.cols()},         {"H", H},
                           {"threads", 1},          {"repeats", repeats}};
  for (const auto& [name, f] : kernels) {
    f();  // warm-up: first-touch allocation
    j[std::string(name) + "_min_s"] = Minimum(repeats, f);
    j[std::string(name) + "_median_s"] = Median(repeats, f);
  }
  std::cout << j.dump() << std::endl;
}

// One LM epoch's parts on the full Jacobian, against the fused blocked epoch.
nlohmann::ordered_json EpochSplit(const sysid::NeuralDataset& d, const Eigen::VectorXd& theta,
                                  int H, int repeats) {
  const int n = static_cast<int>(d.inputs.cols());
  const int P = static_cast<int>(theta.size());
  Eigen::MatrixXd Z = d.inputs.transpose();
  for (int i = 0; i < n; ++i) Z.row(i) /= d.input_names[i] == "a" ? 0.6 : 0.1;
  const Eigen::VectorXd& y = d.targets;
  Eigen::VectorXd r;
  Eigen::MatrixXd J, JtJ(P, P), JtJg(P, P);
  Eigen::VectorXd g;
  double sse = 0;
  const double t_forward = Median(repeats, [&] { sse = sysid::internal::nn::SumSquares(Z, y, H, theta); });
  const double t_jac = Median(repeats, [&] { sysid::internal::nn::Jacobian(Z, y, H, theta, &J); });
  const double t_syrk = Median(repeats, [&] {
    JtJ.setZero();
    JtJ.selfadjointView<Eigen::Lower>().rankUpdate(J.transpose());
  });
  const double t_gemm = Median(repeats, [&] { JtJg.noalias() = J.transpose() * J; });
  Eigen::MatrixXd A = JtJ;
  A.diagonal().array() += 1e-3;
  Eigen::LLT<Eigen::MatrixXd, Eigen::Lower> llt(P);
  Eigen::VectorXd step;
  const double t_chol = Median(repeats, [&] {
    llt.compute(A);
    step = llt.solve(JtJ.col(0));
  });
  // The fused epoch as the trainer runs it: blocked J'J and J'r, one Cholesky, one forward.
  const double t_epoch = Median(repeats, [&] {
    sysid::internal::nn::NormalEquations(Z, y, H, theta, &JtJ, &g, &sse);
    A = JtJ;
    A.diagonal().array() += 1e-3;
    llt.compute(A);
    step = -llt.solve(g);
    sse = sysid::internal::nn::SumSquares(Z, y, H, theta + step);
  });
  nlohmann::ordered_json blocks;
  for (int b : {64, 128, 256, 512, 1024, 4096})
    blocks[std::to_string(b)] =
        Median(repeats, [&] { sysid::internal::nn::NormalEquations(Z, y, H, theta, &JtJ, &g, &sse, b); });
  // Parts an epoch needs: forward for the residuals, Jacobian, J'J, Cholesky, trial forward.
  const double parts = 2 * t_forward + t_jac + t_syrk + t_chol;
  nlohmann::ordered_json j;
  j["what"] = "lm_epoch_split";
  j["N"] = d.size();
  j["P"] = P;
  j["forward_s"] = t_forward;
  j["jacobian_s"] = t_jac;
  j["jtj_syrk_s"] = t_syrk;
  j["jtj_gemm_s"] = t_gemm;
  j["cholesky_s"] = t_chol;
  j["sum_of_parts_s"] = parts;
  j["share"] = {{"forward_x2", 2 * t_forward / parts},
                {"jacobian", t_jac / parts},
                {"jtj_syrk", t_syrk / parts},
                {"cholesky", t_chol / parts}};
  j["syrk_gflops"] = static_cast<double>(d.size()) * P * P / t_syrk / 1e9;
  j["fused_blocked_epoch_s"] = t_epoch;
  j["epoch_over_parts"] = t_epoch / parts;
  j["blocked_normal_equations_s_by_block"] = blocks;
  j["default_block"] = sysid::internal::nn::DefaultBlock(P);
  return j;
}

// One LM epoch by each kernel variant; see the file comment.
void EpochTargets(const sysid::NeuralDataset& d, const Eigen::VectorXd& theta, int H, int repeats,
                  int threads) {
  const int n = static_cast<int>(d.inputs.cols());
  const int P = static_cast<int>(theta.size());
  Eigen::MatrixXd Z = d.inputs.transpose();
  for (int i = 0; i < n; ++i) Z.row(i) /= d.input_names[i] == "a" ? 0.6 : 0.1;
  const Eigen::VectorXd& y = d.targets;
  const double N = static_cast<double>(d.size());
  const double flops = N * P * (P + 1.0) + 2.0 * N * P;  // J'J lower triangle + J'r
  struct Out {
    Eigen::MatrixXd JtJ;
    Eigen::VectorXd g, step;
    double sse = 0, trial = 0;
  };
  auto epoch = [&](const std::function<void(Out*)>& normal,
                   const std::function<double(const Eigen::VectorXd&)>& sumsq, Out* out) {
    normal(out);
    Eigen::MatrixXd A = out->JtJ;
    A.diagonal().array() += 1e-3;
    Eigen::LLT<Eigen::MatrixXd, Eigen::Lower> llt(A);
    out->step = -llt.solve(out->g);
    out->trial = sumsq(theta + out->step);
  };
  auto legacy_normal = [&](Out* o) {
    legacy::NormalEquations(Z, y, H, theta, &o->JtJ, &o->g, &o->sse);
  };
  auto legacy_sumsq = [&](const Eigen::VectorXd& t) { return legacy::SumSquares(Z, y, H, t); };
  Out ref;
  const double t_legacy = Median(repeats, [&] { epoch(legacy_normal, legacy_sumsq, &ref); });
  const Eigen::MatrixXd Lref = ref.JtJ.triangularView<Eigen::Lower>();
  const int all =
      threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  struct Variant {
    const char* isa;
    int threads;
  };
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  rows.push_back({{"kernels", "old (default flags)"},
                  {"threads", 1},
                  {"epoch_s", t_legacy},
                  {"gflops", flops / t_legacy / 1e9},
                  {"max_rel_diff", 0.0}});
  double t_best_1 = 0, t_best_all = 0;
  for (const Variant v : {Variant{"generic", 1}, Variant{"auto", 1}, Variant{"auto", all}}) {
    if (!sysid::internal::nn::SetKernelIsa(v.isa)) continue;
    auto normal = [&](Out* o) {
      sysid::internal::nn::NormalEquations(Z, y, H, theta, &o->JtJ, &o->g, &o->sse, 0, v.threads);
    };
    auto sumsq = [&](const Eigen::VectorXd& t) {
      return sysid::internal::nn::SumSquares(Z, y, H, t, v.threads);
    };
    Out out;
    const double t = Median(repeats, [&] { epoch(normal, sumsq, &out); });
    const Eigen::MatrixXd L = out.JtJ.triangularView<Eigen::Lower>();
    const double diff =
        std::max({(L - Lref).norm() / Lref.norm(), (out.g - ref.g).norm() / ref.g.norm(),
                  std::abs(out.sse - ref.sse) / ref.sse,
                  std::abs(sumsq(theta + ref.step) - ref.trial) / ref.trial});
    rows.push_back({{"kernels", std::string(sysid::internal::nn::KernelIsa())},
                    {"threads", v.threads},
                    {"epoch_s", t},
                    {"gflops", flops / t / 1e9},
                    {"max_rel_diff", diff},
                    {"step_rel_diff", (out.step - ref.step).norm() / ref.step.norm()}});
    if (std::string(v.isa) == "auto") (v.threads == 1 ? t_best_1 : t_best_all) = t;
  }
  sysid::internal::nn::SetKernelIsa("auto");
  nlohmann::ordered_json j{{"what", "lm_epoch_targets"},
                           {"N", d.size()},
                           {"P", P},
                           {"flop_per_epoch", flops},
                           {"variants", rows},
                           {"speedup_vs_old_1thread", t_legacy / t_best_1},
                           {"speedup_vs_old_all_threads", t_legacy / t_best_all},
                           {"thread_scaling", t_best_1 / t_best_all},
                           {"threads", all}};
  std::cout << j.dump() << std::endl;
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string k = argv[i], v = argv[i + 1];
    if (k == "--case")
      a.which = v;
    else if (k == "--data")
      a.data = v;
    else if (k == "--init")
      a.init = v;
    else if (k == "--best")
      a.best = std::stod(v);
    else if (k == "--epochs")
      a.epochs = std::stoi(v);
    else if (k == "--repeats")
      a.repeats = std::stoi(v);
    else if (k == "--threads")
      a.threads = std::stoi(v);
    else {
      std::cerr << "bench_nn: unknown option " << k << '\n';
      return 1;
    }
  }
  try {
    if (a.which == "epoch") {
      const Eigen::VectorXd theta0 = ReadTheta(a.init);
      const std::vector<std::string> inputs =
          theta0.size() % 3 == 1 && a.data.find("_va") == std::string::npos
              ? std::vector<std::string>{"v"}
              : std::vector<std::string>{"v", "a"};
      const auto d = sysid::ReadNeuralDataset(a.data, inputs, "u");
      const int H = static_cast<int>((theta0.size() - 1) / (inputs.size() + 2));
      EpochTargets(d, theta0, H, a.repeats, a.threads);
    } else if (a.which == "kernels") {
      const Eigen::VectorXd theta0 = ReadTheta(a.init);
      const std::vector<std::string> inputs =
          a.data.find("_va") == std::string::npos ? std::vector<std::string>{"v"}
                                                  : std::vector<std::string>{"v", "a"};
      const auto d = sysid::ReadNeuralDataset(a.data, inputs, "u");
      const int H = static_cast<int>((theta0.size() - 1) / (inputs.size() + 2));
      KernelTimes(d, theta0, H, a.repeats);
    } else if (a.which == "v" || a.which == "va") {
      const std::vector<std::string> inputs =
          a.which == "v" ? std::vector<std::string>{"v"} : std::vector<std::string>{"v", "a"};
      const auto d = sysid::ReadNeuralDataset(a.data, inputs, "u");
      const Eigen::VectorXd theta0 = ReadTheta(a.init);
      const int H = static_cast<int>((theta0.size() - 1) / (inputs.size() + 2));
      auto o = PeerProblem(inputs);
      o.hidden = H;
      o.initial_parameters = theta0;
      if (a.which == "v") {
        // Time to reach the target from the peer's start, setup included; then how far each
        // trainer gets with `--epochs` epochs (the paper's rule, the hybrid, Ceres).
        struct Run {
          const char* name;
          sysid::NeuralTrainer trainer;
          bool solve_output;
          bool to_target;
        };
        const Run runs[] = {
            {"lm+output_ls to target", sysid::NeuralTrainer::kLevenbergMarquardt, true, true},
            {"lm+output_ls", sysid::NeuralTrainer::kLevenbergMarquardt, true, false},
            {"lm paper rule (trainlm mu I)", sysid::NeuralTrainer::kLevenbergMarquardt, false,
             false},
            {"ceres lm (dense normal cholesky)", sysid::NeuralTrainer::kCeres, false, false}};
        for (const Run& run : runs) {
          o.trainer = run.trainer;
          o.solve_output_layer = run.solve_output;
          o.goal_mse = run.to_target ? a.best * 1.01 : 0.0;
          o.max_epochs = run.to_target ? 5000 : a.epochs;
          const auto r = sysid::TrainNeuralNetwork(d, nullptr, o);
          nlohmann::ordered_json j{{"what", run.name},
                                   {"target_mse", a.best * 1.01},
                                   {"reached_target", r.train_mse <= a.best * 1.01},
                                   {"epochs", r.epochs},
                                   {"wall_s", r.wall_time_s},
                                   {"final_mse", r.train_mse},
                                   {"stop", sysid::ToString(r.stop)}};
          std::cout << j.dump() << std::endl;
        }
        std::cout << EpochSplit(d, theta0, H, a.repeats).dump() << std::endl;
      } else {
        o.max_epochs = a.epochs;
        std::vector<double> per_epoch;
        for (int rep = 0; rep < 3; ++rep) {
          const auto r = sysid::TrainNeuralNetwork(d, nullptr, o);
          per_epoch.push_back(r.wall_time_s / std::max(r.epochs, 1));
        }
        std::sort(per_epoch.begin(), per_epoch.end());
        nlohmann::ordered_json j{{"what", "lm_per_epoch_va"},
                                 {"P", theta0.size()},
                                 {"epochs", a.epochs},
                                 {"time_per_epoch_s", per_epoch[1]}};
        std::cout << j.dump() << std::endl;
        std::cout << EpochSplit(d, theta0, H, 3).dump() << std::endl;
      }
    } else if (a.which == "sweep") {
      const auto d = sysid::ReadNeuralDataset(a.data, {"v"}, "u");
      sysid::HiddenSweepOptions so;
      so.training.max_epochs = a.epochs;
      so.training.seed = 1;
      so.training.solve_output_layer = true;
      so.threads = a.threads;
      const auto r = sysid::SweepHiddenSize(d, nullptr, nullptr, so);
      nlohmann::ordered_json rows = nlohmann::ordered_json::array();
      for (const auto& row : r.rows)
        rows.push_back({{"H", row.hidden},
                        {"epochs", row.epochs},
                        {"train_mse", row.train_mse},
                        {"wall_s", row.wall_time_s}});
      nlohmann::ordered_json j{{"what", "sweep_16_32_2"},
                               {"max_epochs", a.epochs},
                               {"wall_s", r.wall_time_s},
                               {"rows", rows}};
      std::cout << j.dump() << std::endl;
    } else {
      std::cerr << "bench_nn: --case must be v, va, sweep, epoch or kernels\n";
      return 1;
    }
  } catch (const std::exception& e) {
    std::cerr << "bench_nn: " << e.what() << '\n';
    return 2;
  }
  return 0;
}
