# spatstat fixtures for patterns with duplicated points (paperlib.pointprocess: PointPattern,
# Kest, Lest, Kcross, Lcross, pcf, ppm without hard core).
#
# Sourced by tests/oracle/spatstat_reference.R (run from the project root), or alone:
#   Rscript -e 'source("tests/oracle/common.R"); source("tests/oracle/spatstat_duplicates.R")'
# Writes tests/oracle/duplicates.json.
#
# The pattern: lansing's hickories and maples in [0.5, 1] x [0.5, 1] (302 trees, among them
# lansing's own duplicated hickory at (0.64, 0.983)), plus
#   - a second maple at (0.543, 0.505), 0.005 from the boundary (a duplicate);
#   - a maple at the location of an interior hickory (coincident, different marks: not a
#     duplicate under spatstat's rule, one under rule = "unmark");
#   - two maples at (1, 0.7505), on the boundary (a duplicated pair with boundary distance 0).
# spatstat counts a pair at distance 0 like any other: in K from r = 0 on (its C engines, d <= r)
# or from the first r > 0 (its histogram code, d < r), with edge weight 1 (isotropic and
# translate at d = 0). Recorded on the default r grids and on the grids of summary.json
# (off-lattice, uneven), and Strauss / MultiStrauss fits (no hard core), whose statistics count
# the repeated point as a neighbour at distance 0.
suppressPackageStartupMessages(library(spatstat))
source("tests/oracle/common.R")

all_corrections <- c("none", "border", "isotropic", "translate")
offgrid_r <- function(rmax) seq(0, rmax * (pi / 3.2), length.out = 101)
uneven_r <- function(rmax) rmax * ((0:60) / 60)^1.5

X <- lansing[owin(c(0.5, 1), c(0.5, 1))]
X <- X[marks(X) %in% c("hickory", "maple")]
marks(X) <- droplevels(marks(X))
interior_hickory <- which(marks(X) == "hickory" & bdist.points(X) > 0.1)[1]
added <- ppp(c(0.543, X$x[interior_hickory], 1, 1), c(0.505, X$y[interior_hickory], 0.7505, 0.7505),
             window = Window(X), marks = factor(rep("maple", 4), levels = levels(marks(X))))
X <- superimpose(X, added, W = Window(X))
stopifnot(sum(duplicated(X)) == 3, sum(duplicated(X, rule = "unmark")) == 4)
Y <- unmark(X)

K <- Kest(Y, correction = all_corrections)
rmax <- max(K$r)
cross <- list()
for (pair in list(c("hickory", "maple"), c("maple", "hickory"), c("maple", "maple"))) {
  key <- paste(pair, collapse = "_")
  Kij <- Kcross(X, pair[1], pair[2], correction = all_corrections)
  cross[[paste0("Kcross_", key)]] <- fv_json(Kij, every = 2)
  cross[[paste0("Lcross_offgrid_", key)]] <- fv_json(Lcross(X, pair[1], pair[2], r = offgrid_r(max(Kij$r)),
                                                            correction = all_corrections))
}

fit_json <- function(fit) list(coef_names = names(coef(fit)), coef = unname(coef(fit)),
                               logLik = as.numeric(logLik(fit, warn = FALSE)), vcov = matrix_json(vcov(fit)))
strauss_r <- 0.0205
mstrauss_r <- matrix(c(0.0205, 0.0155, 0.0155, 0.0255), 2, 2)

write_oracle(list(
  description = paste(
    "lansing hickories and maples in [0.5, 1]^2 with duplicated and coincident points added; duplicated",
    "(1-based indices, spatstat's rule and rule = 'unmark'); Kest/Lest/Kcross/Lcross/pcf tables (values to",
    "11 digits); Strauss and MultiStraussHard(hradii = 0) fits, spatstat's default quadrature"
  ),
  pattern = exact_pattern_json(X),
  duplicated = which(duplicated(X)),
  duplicated_unmark = which(duplicated(X, rule = "unmark")),
  Kest = fv_json(K),
  Kest_border_only = fv_json(Kest(Y, correction = "border"), every = 4),
  Kest_uneven = fv_json(Kest(Y, r = uneven_r(rmax), correction = all_corrections)),
  Lest_offgrid = fv_json(Lest(Y, r = offgrid_r(rmax), correction = all_corrections)),
  cross = cross,
  pcf = fv_json(pcf(Y, correction = c("translate", "isotropic")), every = 2),
  strauss = c(list(r = strauss_r), fit_json(ppm(Y ~ 1, Strauss(strauss_r)))),
  multistrauss = c(list(iradii = matrix_json(mstrauss_r)),
                   fit_json(ppm(X ~ marks, MultiStraussHard(iradii = mstrauss_r, hradii = matrix(0, 2, 2)))))
), "tests/oracle/duplicates.json")
