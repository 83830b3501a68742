// The on-board spectra's cost: streaming Welch PSD of 8 three-axis accelerometers at 4 kHz (24
// channels, 4096-point segments every 2048 samples) and the whole vibration pipeline (grid, damper
// and tire spectra per axle and cell, mode and spatial spectra) for 8 sensors at 4 kHz, each as a
// fraction of one core. Also the FFT's measurements behind docs/spectra.md: Eigen's FFT in double
// and in float (the precision a float-only KissFFT would give), time per transform and the PSD's
// relative error against double.
//   bench_spectra [SECONDS] [--dump FILE]   FILE: the 24 channels (float64, channel after channel)
//   and their PSDs for tests/bench/spectra_vs_scipy.py.
#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstring>
#include <map>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <unsupported/Eigen/FFT>

#include "roadload/contact_forces.hpp"
#include "roadload/spectra/welch.hpp"
#include "roadload/vibration.hpp"
#include "vehicles.hpp"

namespace {

using Clock = std::chrono::steady_clock;
constexpr double kFs = 4000.0;
constexpr std::size_t kChannels = 24, kSensors = 8;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Body and axle modes, a joint line and noise: what a truck's accelerometers carry.
std::vector<std::vector<double>> signals(double duration_s) {
  std::mt19937_64 rng(2014);
  std::normal_distribution<double> noise(0.0, 0.05);
  const auto n = static_cast<std::size_t>(duration_s * kFs);
  std::vector<std::vector<double>> x(kChannels, std::vector<double>(n));
  for (std::size_t c = 0; c < kChannels; ++c) {
    const double g = c % 3 == 2 ? 9.81 : 0.0, phase = 0.3 * static_cast<double>(c);
    for (std::size_t i = 0; i < n; ++i) {
      const double t = static_cast<double>(i) / kFs;
      x[c][i] = g + 0.4 * std::sin(2 * std::numbers::pi * 1.5 * t + phase) + 0.2 * std::sin(2 * std::numbers::pi * 2.93 * t) +
                0.8 * std::sin(2 * std::numbers::pi * 12.3 * t + 2 * phase) + noise(rng);
    }
  }
  return x;
}

double streaming_welch(const std::vector<std::vector<double>>& x, std::vector<std::vector<double>>& psd) {
  const roadload::spectra::WelchConfig cfg{kFs, 4096, 2048};
  std::vector<roadload::spectra::WelchPsd> ch;
  ch.reserve(kChannels);
  for (std::size_t c = 0; c < kChannels; ++c) ch.emplace_back(cfg);
  const auto t0 = Clock::now();
  for (std::size_t i = 0; i < x[0].size(); ++i)
    for (std::size_t c = 0; c < kChannels; ++c) ch[c].push(x[c][i]);
  const double wall = seconds_since(t0);
  psd.assign(kChannels, std::vector<double>(roadload::spectra::bin_count(cfg)));
  for (std::size_t c = 0; c < kChannels; ++c) ch[c].density(psd[c]);
  return wall;
}

double pipeline(const std::vector<std::vector<double>>& x) {
  // The MnROAD layout: five axles, eight sensors as the report mounted them.
  const char* positions[kSensors] = {"tractor-front-axle-left",   "tractor-front-frame-left", "tractor-drive1-axle-left",
                                     "tractor-drive1-frame-left", "tractor-drive2-axle-left", "trailer-axle1-left",
                                     "trailer-axle1-frame-left",  "trailer-axle2-left"};
  std::vector<roadload::SensorPlacement> placements;
  std::vector<roadload::VibrationSensor> sensors;
  for (std::size_t s = 0; s < kSensors; ++s) {
    placements.push_back({static_cast<std::int64_t>(s), "accelerometer", positions[s]});
    sensors.push_back({static_cast<std::uint8_t>(s), "S" + std::to_string(s), kFs});
  }
  auto layout = roadload::build_axle_layout(placements, roadload::shipped::mnroad_vehicle());
  if (!layout) {
    std::fprintf(stderr, "bench_spectra: %s\n", layout.error().to_string().c_str());
    return 0;
  }
  constexpr std::size_t kCells = 40;
  std::vector<int> group(kCells);
  for (std::size_t c = 0; c < kCells; ++c) group[c] = static_cast<int>(c % 2);
  roadload::VibrationAnalysis va(layout.value(), sensors, kCells, group, 2);
  const double speed = 13.4, cell_m = 150.0;
  std::array<int, 5> cells{};
  const auto t0 = Clock::now();
  for (std::size_t i = 0; i < x[0].size(); ++i) {
    const double t = static_cast<double>(i) / kFs;
    if (i % 400 == 0) {  // placements at 10 Hz
      for (std::size_t a = 0; a < cells.size(); ++a)
        cells[a] = static_cast<int>(std::fmod((speed * t - layout.value().axles[a].position_m) / cell_m + kCells, kCells));
      va.set_axle_cells(roadload::capture_time_from_ns(std::llround(t * 1e9)), cells, speed, speed * t);
    }
    for (std::size_t s = 0; s < kSensors; ++s) {
      roadload::AccelSample a;
      a.t = roadload::capture_time_from_ns(std::llround((t + 1.0) * 1e9) + static_cast<std::int64_t>(s) * 1000);
      a.sensor = static_cast<std::uint8_t>(s);
      a.z_mps2 = x[3 * s + 2][i];
      va.push(a);
    }
  }
  return seconds_since(t0);
}

template <typename Scalar>
double fft_ns(std::size_t n, std::vector<std::complex<Scalar>>& out) {
  std::vector<Scalar> in(n);
  for (std::size_t i = 0; i < n; ++i) in[i] = static_cast<Scalar>(std::sin(0.01 * static_cast<double>(i * i % 977)));
  Eigen::FFT<Scalar> fft;
  fft.SetFlag(Eigen::FFT<Scalar>::HalfSpectrum);
  out.resize(n / 2 + 1);
  fft.fwd(out.data(), in.data(), static_cast<Eigen::Index>(n));
  constexpr int kReps = 2000;
  const auto t0 = Clock::now();
  for (int r = 0; r < kReps; ++r) fft.fwd(out.data(), in.data(), static_cast<Eigen::Index>(n));
  return seconds_since(t0) * 1e9 / kReps;
}

}  // namespace

int main(int argc, char** argv) {
  double duration_s = 60;
  std::string dump;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--dump") == 0 && i + 1 < argc) {
      dump = argv[++i];
    } else {
      duration_s = std::atof(argv[i]);
    }
  }
  if (!(duration_s >= 2)) {
    std::fprintf(stderr, "usage: bench_spectra [SECONDS>=2] [--dump FILE]\n");
    return 64;
  }
  const auto x = signals(duration_s);
  const double samples = static_cast<double>(kChannels) * static_cast<double>(x[0].size());
  std::vector<std::vector<double>> psd;
  const double welch_s = streaming_welch(x, psd);
  const double pipe_s = pipeline(x);
  std::printf("bench_spectra: %.0f s of 8 three-axis accelerometers at 4 kHz (%.2e samples)\n", duration_s, samples);
  std::printf("  streaming Welch PSD, 24 channels, 4096-point segments every 2048: %.1f ns/sample, %.3f %% of a core (goal < 1 %%)\n",
              welch_s * 1e9 / samples, 100.0 * welch_s / duration_s);
  std::printf("  vibration pipeline, 8 sensors (grid, per-axle damper/tire spectra, modes, spatial): %.3f %% of a core\n",
              100.0 * pipe_s / duration_s);

  std::vector<std::complex<double>> fd;
  std::vector<std::complex<float>> ff;
  const double nd = fft_ns<double>(4096, fd), nf = fft_ns<float>(4096, ff);
  double worst = 0, peak = 0;
  for (std::size_t k = 0; k < fd.size(); ++k) peak = std::max(peak, std::norm(fd[k]));
  for (std::size_t k = 0; k < fd.size(); ++k) {
    const double ref = std::norm(fd[k]);
    if (ref > 1e-6 * peak) worst = std::max(worst, std::abs(static_cast<double>(std::norm(ff[k])) - ref) / ref);
  }
  std::printf(
      "  Eigen FFT, 4096 real points: double %.1f us, float %.1f us (ratio %.2f); float |X|^2 against double: worst %.1e relative "
      "(bins above 1e-6 of the peak)\n",
      nd / 1e3, nf / 1e3, nd / nf, worst);
  std::printf("  16 channels at 4 kHz need %.0f transforms of 4096 points a second: %.3f %% of a core in double\n",
              16 * 4000.0 / 2048.0, 100.0 * 16 * 4000.0 / 2048.0 * nd * 1e-9);

  if (!dump.empty()) {
    std::FILE* f = std::fopen(dump.c_str(), "wb");
    if (!f) {
      std::fprintf(stderr, "bench_spectra: %s: cannot create\n", dump.c_str());
      return 73;
    }
    for (const auto& c : x) std::fwrite(c.data(), sizeof(double), c.size(), f);
    for (const auto& p : psd) std::fwrite(p.data(), sizeof(double), p.size(), f);
    std::fclose(f);
    std::printf("  dumped %zu channels x %zu samples and their PSDs to %s\n", kChannels, x[0].size(), dump.c_str());
  }
  std::printf("welch_ns_per_sample=%.3f\n", welch_s * 1e9 / samples);
  return 0;
}
