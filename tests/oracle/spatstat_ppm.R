# spatstat fixtures for paperlib.pointprocess.fit (maximum pseudolikelihood, quadrature schemes).
#
# Sourced by tests/oracle/spatstat_reference.R (run from the project root), or alone:
#   Rscript -e 'source("tests/oracle/common.R"); source("tests/oracle/spatstat_ppm.R")'
# Writes tests/oracle/ppm.json: the three data sets (coordinates, marks, window, 17 digits, so
# the tests need no R) and, for each fit, spatstat's coefficients, both variance estimates,
# the log pseudolikelihood and a summary of the quadrature scheme; plus ppm timings.
#
# Fits (interaction radii chosen here and written into the fixture):
#   cells        StraussHard(r = 0.1, hc = 0.05)   default nd; nd = 256 (tiles 32 x 32); nd = 512
#   cells        StraussHard(r = 0.1), hc estimated by spatstat (minimum nn distance * n/(n+1))
#   swedishpines Strauss(r = 7)                    default nd; nd = 100 (tiles 50 x 50); nd = 512
#   amacrine     ~marks + MultiStraussHard(iradii), hradii estimated by spatstat
#                (minimum cross distance * m/(m+1), m = the smaller count); default nd; nd = 128
#                (tiles 64 x 64); nd = 512. The radii sit on the half-lattice of amacrine's
#                4-decimal coordinates, so no pair distance equals a radius exactly (no tie rule
#                can matter).
# The nd = 512 fits are the near-converged references the tests hold our default (finer)
# scheme to; the default-nd and given-nd fits are reproduced to 1e-4.
suppressPackageStartupMessages(library(spatstat))
source("tests/oracle/common.R")

pattern_json <- function(X) {
  W <- Window(X)
  stopifnot(is.rectangle(W))
  out <- list(x = X$x, y = X$y, window = list(type = "rectangle", xrange = W$xrange, yrange = W$yrange))
  if (is.multitype(X)) {
    out$marks <- as.character(marks(X))
    out$categories <- levels(marks(X))
  }
  out
}

fit_json <- function(name, data, fit, settings, keep_weights = FALSE) {
  Q <- quad.ppm(fit)
  w <- w.quad(Q)
  inter <- fit$interaction$par
  out <- c(list(name = name, data = data), settings, list(
    interaction = fit$interaction$name,
    hc = if (!is.null(inter$hc)) inter$hc else NULL,
    hradii = if (!is.null(inter$hradii)) matrix_json(inter$hradii) else NULL,
    iradii = if (!is.null(inter$iradii)) matrix_json(inter$iradii) else NULL,
    rbord = fit$rbord,
    coef_names = names(coef(fit)),
    coef = unname(coef(fit)),
    vcov = matrix_json(vcov(fit)),                      # spatstat's default (Coeurjolly-Rubak)
    vcov_hessian = matrix_json(vcov(fit, hessian = TRUE)),  # inverse Fisher information of log-PL
    logLik = as.numeric(logLik(fit, warn = FALSE)),
    quadrature = list(
      nd = Q$param$dummy$nd[1],
      ntile = Q$param$weight$ntile[1],
      n_data = npoints(Q$data),
      n_dummy = npoints(Q$dummy),
      total_weight = sum(w),
      n_fitted = sum(getglmsubset(fit))
    )
  ))
  if (keep_weights) out$quadrature$weights <- w
  out
}

timed <- function(expr, repeats) {
  expr <- substitute(expr)
  env <- parent.frame()
  eval(expr, env)  # warm-up
  median(vapply(seq_len(repeats), function(i) system.time(eval(expr, env))[["elapsed"]], 0))
}

cells_r <- 0.1
cells_hc <- 0.05
pines_r <- 7
ama_iradii <- matrix(c(0.05525, 0.03025, 0.03025, 0.06025), 2, 2,
                     dimnames = list(c("off", "on"), c("off", "on")))

fits <- list()
add <- function(x) fits[[length(fits) + 1]] <<- x

for (nd in list(NULL, 256, 512)) {
  fit <- ppm(cells ~ 1, StraussHard(r = cells_r, hc = cells_hc), nd = nd)
  add(fit_json(paste0("cells_strausshard_nd", if (is.null(nd)) "default" else nd), "cells", fit,
               list(r = cells_r, nd_given = nd), keep_weights = is.null(nd)))
}
fit <- ppm(cells ~ 1, StraussHard(r = cells_r))
add(fit_json("cells_strausshard_hc_estimated", "cells", fit, list(r = cells_r, nd_given = NULL)))

for (nd in list(NULL, 100, 512)) {
  fit <- ppm(swedishpines ~ 1, Strauss(r = pines_r), nd = nd)
  add(fit_json(paste0("swedishpines_strauss_nd", if (is.null(nd)) "default" else nd), "swedishpines", fit,
               list(r = pines_r, nd_given = nd)))
}

for (nd in list(NULL, 128, 512)) {
  fit <- ppm(amacrine ~ marks, MultiStraussHard(iradii = ama_iradii), nd = nd)
  add(fit_json(paste0("amacrine_multistrausshard_nd", if (is.null(nd)) "default" else nd), "amacrine", fit,
               list(nd_given = nd)))
}

# ppm timings: StraussHard on uniform points in the unit square, default quadrature, hard core
# estimated by spatstat; r shrinks with n so that a point has about 7.9 neighbours within r.
timing_radius <- function(n) 0.05 * sqrt(1000 / n)
timings <- list()
for (n in c(1000, 10000)) {
  set.seed(1)
  X <- runifpoint(n)
  r <- timing_radius(n)
  timings[[as.character(n)]] <- list(
    r = r,
    repeats = 7,
    seconds = timed(ppm(X ~ 1, StraussHard(r = r)), 7)
  )
}

write_oracle(list(
  description = paste(
    "spatstat ppm fits (maximum pseudolikelihood, border correction, Berman-Turner grid quadrature):",
    "coef in spatstat's parametrisation; vcov = vcov(fit) (Coeurjolly-Rubak sandwich, spatstat's default);",
    "vcov_hessian = vcov(fit, hessian = TRUE) (inverse Fisher information of the log pseudolikelihood);",
    "logLik = logLik(fit) (log pseudolikelihood). Timings: median elapsed seconds of ppm(X ~ 1, StraussHard(r))",
    "on runifpoint(n), r = 0.05 sqrt(1000 / n), default quadrature."
  ),
  data = list(cells = pattern_json(cells), swedishpines = pattern_json(swedishpines),
              amacrine = pattern_json(amacrine)),
  fits = fits,
  timings = timings
), "tests/oracle/ppm.json")
