// sysid train / sweep / predict: outputs, exit codes, messages, no partial files.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>

#include "support/test_support.hpp"
#include "sysid/nn.hpp"

using Catch::Matchers::Contains;
using sysid::test::RunCli;

namespace {

// v [m/s] ~ U(-0.1, 0.1), a [m/s^2] = 0, u [V] smooth in v plus 0.05 V noise.
std::string MakeCsv(int N, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> U(-0.1, 0.1);
  std::normal_distribution<double> noise(0.0, 0.05);
  std::ostringstream s;
  s.precision(17);
  s << "t,v,a,u\n";
  for (int k = 0; k < N; ++k) {
    const double v = U(gen);
    s << 1e-3 * k << ',' << v << ',' << 0.3 * std::sin(0.01 * k) << ','
      << 2.0 * std::sin(25.0 * v) + 8.0 * v + noise(gen) << '\n';
  }
  return s.str();
}

}  // namespace

TEST_CASE("sysid train writes a model and reports MSEs, predict reproduces them", "[nn][cli]") {
  sysid::test::TempDir dir;
  sysid::test::WriteText(dir / "train.csv", MakeCsv(400, 1u));
  sysid::test::WriteText(dir / "test.csv", MakeCsv(200, 2u));
  const auto r = RunCli({"train", "--train", dir / "train.csv", "--test", dir / "test.csv",
                         "--inputs", "v", "--output", "u", "--hidden", "6", "--seed", "3",
                         "--max-epochs", "60", "-o", dir / "nn.json", "--json"});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key : {"train_mse", "test_mse", "epochs", "stop_reason"}) CHECK(j.contains(key));
  CHECK(j["epochs"].get<int>() <= 60);
  // The written model reproduces the reported numbers through the library.
  const auto net = sysid::ReadNeuralNetwork(dir / "nn.json");
  CHECK(net.hidden_size() == 6);
  const auto test = sysid::ReadNeuralDataset(dir / "test.csv", {"v"}, "u");
  CHECK(sysid::MeanSquaredError(net, test) == Approx(j["test_mse"].get<double>()).epsilon(1e-9));

  const auto p = RunCli(
      {"predict", "--nn", dir / "nn.json", dir / "test.csv", "-o", dir / "pred.csv", "--json"});
  INFO(p.err);
  REQUIRE(p.exit_code == 0);
  const auto pj = nlohmann::json::parse(p.out);
  CHECK(pj["mse"].get<double>() == Approx(j["test_mse"].get<double>()).epsilon(1e-12));
  sysid::ReadOptions ro;
  ro.required_columns = {"v", "u_nn"};
  ro.any_of_columns = {};
  const auto pred = sysid::ReadRecording(dir / "pred.csv", ro);
  Eigen::MatrixXd X = pred.column("v");
  CHECK((pred.column("u_nn") - net.EvaluateBatch(X)).cwiseAbs().maxCoeff() < 1e-12);
}

TEST_CASE("sysid sweep tabulates hidden sizes and writes the chosen network", "[nn][cli]") {
  sysid::test::TempDir dir;
  sysid::test::WriteText(dir / "train.csv", MakeCsv(300, 3u));
  sysid::test::WriteText(dir / "test.csv", MakeCsv(200, 4u));
  const auto r =
      RunCli({"sweep", "--train", dir / "train.csv", "--test", dir / "test.csv", "--hidden",
              "2:6:2", "--max-epochs", "30", "--inputs", "v,a", "-o", dir / "best.json", "--json"});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.out);
  REQUIRE(j["rows"].size() == 3);
  double best = INFINITY;
  int best_h = 0;
  for (const auto& row : j["rows"])
    if (row["test_mse"].get<double>() < best) {
      best = row["test_mse"].get<double>();
      best_h = row["hidden"].get<int>();
    }
  CHECK(j["chosen_hidden"].get<int>() == best_h);
  CHECK(sysid::ReadNeuralNetwork(dir / "best.json").hidden_size() == best_h);
  CHECK(sysid::ReadNeuralNetwork(dir / "best.json").input_count() == 2);
}

TEST_CASE("train and sweep give bit-identical networks on 1 and 2 threads", "[nn][cli][threads]") {
  sysid::test::TempDir dir;
  sysid::test::WriteText(dir / "train.csv", MakeCsv(1500, 5u));
  sysid::test::WriteText(dir / "test.csv", MakeCsv(200, 6u));
  for (const std::string command : {"train", "sweep"}) {
    std::vector<Eigen::VectorXd> params;
    for (const std::string threads : {"1", "2"}) {
      const auto out = dir / (command + threads + ".json");
      std::vector<std::string> args = {command,     "--train",        dir / "train.csv",
                                       "--test",    dir / "test.csv", "--inputs",
                                       "v,a",       "--max-epochs",   "12",
                                       "--threads", threads,          "-o",
                                       out};
      if (command == "sweep") args.insert(args.end(), {"--hidden", "3:5:2"});
      const auto r = RunCli(args);
      INFO(r.err);
      REQUIRE(r.exit_code == 0);
      params.push_back(sysid::ReadNeuralNetwork(out).parameters());
    }
    CHECK(params[0] == params[1]);
  }
}

TEST_CASE("bad input and options: exit codes, messages, no output file", "[nn][cli]") {
  sysid::test::TempDir dir;
  sysid::test::WriteText(dir / "train.csv", MakeCsv(50, 5u));
  sysid::test::WriteText(dir / "bad.csv", "v,u\n0.01,0.5\n0.02,abc\n");
  const std::string out = dir / "nn.json";
  auto r = RunCli({"train", "--train", dir / "bad.csv", "-o", out});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains("bad.csv:3:"));
  r = RunCli({"train", "--train", dir / "train.csv", "--inputs", "v,x", "-o", out});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains("'x'"));
  r = RunCli({"train", "--train", dir / "train.csv", "--momentum", "1.5", "-o", out});
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.err, Contains("momentum"));
  r = RunCli({"train", "--train", dir / "train.csv", "--input-range", "q=0:1", "-o", out});
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.err, Contains("--input-range"));
  r = RunCli({"sweep", "--train", dir / "train.csv", "--hidden", "8:4", "-o", out});
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.err, Contains("LAST < FIRST"));
  CHECK_FALSE(std::filesystem::exists(out));

  sysid::test::WriteText(dir / "broken.json", "{\n  \"type\": \"tanh-mlp\",\n  \"hidden\": ,\n}");
  r = RunCli({"predict", "--nn", dir / "broken.json", dir / "train.csv", "-o", dir / "p.csv"});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains("broken.json:3:13"));
  CHECK_FALSE(std::filesystem::exists(dir / "p.csv"));
}

TEST_CASE("sysid irreducible: v determines u, a adds only noise, bad input is named",
          "[nn][cli][irreducible]") {
  // u = 2 v^2 + 10 v + e (e uniform, width 0.2 V: variance 0.04/12), a independent noise: the
  // floor given v is e's variance (closed form); given (v, a) it cannot be smaller than that.
  sysid::test::TempDir dir;
  std::ostringstream csv;
  csv << "t,u,v,a\n";
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> uni(-0.5, 0.5);
  for (int k = 0; k < 6000; ++k) {
    const double v = 0.1 * std::sin(k * 1e-3);
    csv << k * 1e-3 << ',' << 2 * v * v + 10 * v + 0.2 * uni(rng) << ',' << v << ','
        << uni(rng) << '\n';
  }
  sysid::test::WriteText(dir / "rec.csv", csv.str());
  const auto r = RunCli({"irreducible", dir / "rec.csv", "--inputs", "v", "--inputs", "v,a",
                         "--neighbours", "20", "--json"});
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.out);
  REQUIRE(j["rows"].size() == 2);
  const double v_only = j["rows"][0]["irreducible_mse_estimate"].get<double>();
  const double both = j["rows"][1]["irreducible_mse_estimate"].get<double>();
  CHECK(v_only == Approx(0.04 / 12).epsilon(0.08));
  CHECK(both > 0.95 * v_only);
  CHECK(j["rows"][0]["interval95"][0].get<double>() < v_only);
  CHECK(j["rows"][0]["interval95"][1].get<double>() > v_only);
  // An estimate above its subset's is marked as the estimate's bias, never left as a floor.
  CHECK(j["rows"][1]["estimate_above_subset"] ==
        (both > v_only ? nlohmann::json("v") : nlohmann::json(nullptr)));
  CHECK(j["rows"][0]["estimate_above_subset"].is_null());
  CHECK(j["rows"][1]["inputs"] == nlohmann::json({"v", "a"}));

  const auto missing = RunCli({"irreducible", dir / "rec.csv", "--inputs", "v,x"});
  CHECK(missing.exit_code == 2);
  CHECK_THAT(missing.err, Contains("rec.csv") && Contains("x"));
  const auto empty = RunCli({"irreducible", dir / "rec.csv", "--inputs", "v,"});
  CHECK(empty.exit_code == 1);
  CHECK_THAT(empty.err, Contains("--inputs"));
  const auto k = RunCli({"irreducible", dir / "rec.csv", "--neighbours", "1"});
  CHECK(k.exit_code == 1);
}
