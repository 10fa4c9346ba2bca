# spatstat rmh oracle: Monte Carlo summaries of Strauss hard-core simulations, and rmh speed.
#
# Sourced by tests/oracle/spatstat_reference.R (run from the project root); writes
# tests/oracle/rmh.json. About a minute on a 2-core machine.
#
# Monte Carlo part (tests/test_pointprocess_simulate.py compares paperlib's rmh with it):
# for a StraussHard model (~50 points) and a two-type MultiStraussHard model in Hurtut's
# regime (moderate gamma, hard cores; a sparse type of large elements and a dense type of
# small ones), nsim independent rmh realisations in the unit square, expand = 1 and
# periodic = FALSE so that the window is the simulation window itself; recorded: mean and
# sd of the count of each type, and mean and sd of the border-corrected L (spatstat's
# L = sqrt(K / pi)) on a fixed r grid: of the pattern, and for the multitype model also
# Lcross(0, 1). L is computed on a fine grid (513 values) and kept every 32nd value, so
# that Kcross's one-step lag in border eligibility (see shared notes) is negligible.
#
# Speed part: rmh steps per second with spatstat's default moves (rmhcontrol's p = 0.9 shifts,
# q = 0.9 births among the other proposals; written out below so that the benchmark can match them),
# starting from an equilibrium pattern, for StraussHard at ~50, ~630 and ~1e4 points (one
# model family scaled to the point count) and a three-type MultiStraussHard (~300 points).
source("tests/oracle/common.R")
suppressPackageStartupMessages(library(spatstat))

set.seed(20090301)
W <- square(1)
nsim <- 200
nrep <- 1e5
r_fine <- seq(0, 0.2, length.out = 513)
keep <- seq(33, 513, by = 32)  # r = 0.0125, 0.025, ..., 0.2

# StraussHard scaled to a target point count n: beta = 2 n, r = 0.08 sqrt(50 / n), hc = r / 4
strauss_family <- function(n) {
  r <- 0.08 * sqrt(50 / n)
  list(beta = 2 * n, gamma = 0.3, r = r, hc = r / 4)
}
strauss_model <- function(par) rmhmodel(cif = "straush", par = par, w = W)
multi_model <- function(par) {
  types <- as.character(seq_along(par$beta) - 1)
  rmhmodel(cif = "straushm", par = list(beta = par$beta, gamma = par$gamma, iradii = par$r, hradii = par$hc),
           w = W, types = types)
}
control <- function(nrep) rmhcontrol(nrep = nrep, p = 0.9, q = 0.9, expand = 1, periodic = FALSE)

two_type <- list(
  beta = c(60, 120),
  gamma = matrix(c(0.2, 0.5, 0.5, 0.4), 2, 2),
  r = matrix(c(0.10, 0.07, 0.07, 0.05), 2, 2),
  hc = matrix(c(0.04, 0.02, 0.02, 0.015), 2, 2)
)
three_type <- list(
  beta = c(240, 160, 320),
  gamma = matrix(c(0.3, 0.5, 0.4, 0.5, 0.2, 0.5, 0.4, 0.5, 0.4), 3, 3),
  r = matrix(c(0.06, 0.05, 0.045, 0.05, 0.07, 0.05, 0.045, 0.05, 0.05), 3, 3) / sqrt(2),
  hc = matrix(c(0.02, 0.015, 0.01, 0.015, 0.025, 0.015, 0.01, 0.015, 0.015), 3, 3) / sqrt(2)
)

border_L <- function(X) Lest(X, r = r_fine, correction = "border")$border[keep]
cross_L <- function(X) Lcross(X, "0", "1", r = r_fine, correction = "border")$border[keep]
summarise <- function(values) list(mean = colMeans(values), sd = apply(values, 2, sd))

monte_carlo <- function(model, n_start, multitype) {
  began <- proc.time()[["elapsed"]]
  sims <- rmh(model, start = list(n.start = n_start), control = control(nrep), nsim = nsim, verbose = FALSE)
  counts <- t(sapply(sims, function(X) if (multitype) as.vector(table(marks(X))) else npoints(X)))
  if (!multitype) counts <- t(counts)
  out <- list(nsim = nsim, nrep = nrep, counts = summarise(counts),
              L = summarise(t(sapply(sims, function(X) border_L(unmark(X))))))
  if (multitype) out$Lcross_0_1 <- summarise(t(sapply(sims, cross_L)))
  out$seconds <- proc.time()[["elapsed"]] - began
  out
}

steps_per_second <- function(model, n_start, steps = 5e5, repeats = 3) {
  burn_in <- max(2e5, 100 * sum(n_start))  # from random points to about the equilibrium count
  start <- rmh(model, start = list(n.start = n_start), control = control(burn_in), verbose = FALSE)
  seconds <- replicate(repeats, system.time(
    rmh(model, start = list(x.start = start), control = control(steps), verbose = FALSE)
  )[["elapsed"]])
  list(points = npoints(start), steps = steps, steps_per_second = steps / median(seconds))
}

message("rmh Monte Carlo: StraussHard")
strauss_par <- strauss_family(50)
strauss_mc <- monte_carlo(strauss_model(strauss_par), 50, multitype = FALSE)
message("rmh Monte Carlo: two-type MultiStraussHard")
multi_mc <- monte_carlo(multi_model(two_type), c(20, 70), multitype = TRUE)

message("rmh timings")
timing <- list(
  StraussHard = lapply(c(`50` = 50, `630` = 630, `10000` = 10000), function(n) {
    c(list(model = strauss_family(n)),
      steps_per_second(strauss_model(strauss_family(n)), n, steps = if (n > 1000) 5e4 else 5e5))
  }),
  MultiStraussHard3 = c(list(model = three_type), steps_per_second(multi_model(three_type), c(100, 50, 150)))
)

write_oracle(list(
  description = paste("spatstat rmh (expand = 1, periodic = FALSE) in the unit square: Monte Carlo means and sds",
                      "of counts and border-corrected L = sqrt(K/pi) over nsim realisations; steps/s with",
                      "spatstat's default moves (p = 0.9, q = 0.9) from an equilibrium start"),
  window = list(xrange = c(0, 1), yrange = c(0, 1)),
  r = r_fine[keep],
  StraussHard = c(list(model = strauss_par, n_start = 50), strauss_mc),
  MultiStraussHard = c(list(model = two_type, n_start = c(20, 70)), multi_mc),
  timing = timing
), "tests/oracle/rmh.json")
