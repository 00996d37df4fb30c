#pragma once
// How sure a tray test's CV at a bout width is: its 95 % interval from the test's own repeatability —
// the differences between its passes — so a report can say PASS, MARGINAL or FAIL (cv_verdict.hpp).
//
// The CV is a function of the trays' masses (the mean of the passes per tray, overlapped over the bout;
// missing trays left out as cv_without_missing.hpp says). Each tray's mean carries the Type A standard
// uncertainty of a mean of P readings, u²(m̄_i) = s_i² / P (JCGM 100:2008 "GUM" 4.2.3), s_i² the sample
// variance of the tray over the passes after each pass is scaled to the mean pass's total (a pass that
// carried more fertiliser scales the whole pattern, which leaves the CV alone: pass_scatter.hpp does the
// same). The trays are read independently, so the law of propagation of uncertainty for uncorrelated
// inputs (GUM 5.1.2, eq. 10) gives
//     u²(CV) = Σ_i (∂CV/∂m̄_i)² u²(m̄_i),
// the sensitivities by central differences of the CV the report prints. The interval is CV ± 1.96 u
// (normal coverage; the degrees of freedom, (P − 1) per tray holding mass, are many), clipped at 0. A
// tray read in fewer than two passes takes the pooled relative variance of the trays read in two or
// more. With one pass there is no repeatability to estimate: no interval (the verdict then compares
// the CV itself).
//
// What it does not cover: that the day's test stands for every day (wind, another batch) — a
// repeatability interval, not a prediction interval for the field.
#include "libspread/analysis/calibration/tray_csv.hpp"
#include "libspread/analysis/metrics/metrics.hpp"

namespace spread::calibration {

struct TrayCvInterval {
  bool available = false;      // at least two passes and a finite CV
  double cv = 0.0;             // fraction, as cv_without_missing gives it
  double standard_uncertainty = 0.0;  // u(CV), fraction
  double low = 0.0, high = 0.0;       // cv ∓ 1.96 u, low clipped at 0
};

// At a bout of `bout_tray_count` whole trays (metrics::bout_tray_count) of the test's layout.
TrayCvInterval tray_cv_interval(const TrayTest& test, int bout_tray_count, metrics::Overlap overlap);

}  // namespace spread::calibration
