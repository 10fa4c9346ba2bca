# rrcov fixtures for paperlib.arrangement.robpca (ROBPCA, Hubert, Rousseeuw & Vanden Branden 2005).
#
# Run from the project root:
#   Rscript tests/oracle/rrcov_robpca.R
# Writes tests/oracle/robpca.json, so the tests need no R:
#   data          the data sets, every value as a "%.17g" string (exact17) so Python reads the very
#                 doubles R used:
#                   planted   60 points of an elongated 4-D Gaussian (sd 3, 1.2, 0.7, 0.4 along the
#                             columns of a random rotation) + 8 gross outliers 10 units along the
#                             second axis; with the true first direction and the outlier rows
#                   small     the same recipe at Hurtut's scale: 13 points + 2 outliers (n = 15, so
#                             rrcov's outlyingness uses all 105 pairs and is deterministic)
#                   hbk       robustbase's Hawkins-Bradu-Kass data, all 4 columns (14 outliers)
#                   starsCYG  robustbase's star cluster CYG OB1, p = 2 (4 giants + a few others)
#                   drawn_*   Hurtut's appearance features (elongation, unwrapped orientation,
#                             extremities, crossings, normalised) of hand-drawn glyph arrangements
#                             from paperlib.datasets.categorization_cases("main", rng=0): the
#                             matrices categorize(method = "paper") hands to ROBPCA, non-identical
#                             elements of 1 to 5 types (computed by the project's Python, read here)
#   fits          PcaHubert(X, k, alpha = 0.75, mcd = FALSE) -- the full ROBPCA algorithm; with the
#                 default mcd = TRUE and n >= 5 p rrcov would instead take the PCA of one MCD --
#                 for k = 1, 2 and R seeds 1..5 (the MCD in the k-dimensional subspace draws its
#                 starts from R's random state): loadings (p x k, row by row), eigenvalues, center,
#                 score and orthogonal distances, their cutoffs, the flagged rows (0-based), h.
#                 (rrcov's answer does not move with the seed: its MCD finds the same optimum.)
#   permutations  the same fits (seed 1) on 20 random row orders of each data set with n > 22:
#                 rrcov then takes its 250 directions through other pairs (its generator draws
#                 row numbers from a fixed seed), which shows how far ROBPCA's answer moves with
#                 the directions alone -- the yardstick for ours, which draws other directions.
#                 Loadings, eigenvalues, and flagged rows as rows of the original data.
#   outlyingness  rrcov's Stahel-Donoho outlyingness of `small` (all pairs: no randomness).
#   unimcd        rrcov's reweighted univariate MCD (location, scale) of a few columns.
#   covmcd        robustbase's covMcd(alpha = 0.75) of starsCYG and of its first column: raw and
#                 reweighted center and scatter, and the raw h-subset (0-based; p > 1 only).
#   corrections   robustbase's small-sample correction factors of the raw and reweighted MCD
#                 (Pison et al. 2002) for k = 1..4, n = 10, 47, 200, alpha = 0.75, 0.9.
suppressPackageStartupMessages(library(rrcov))
source("tests/oracle/common.R")

exact_rows <- function(m) unname(lapply(seq_len(nrow(m)), function(i) exact17(unname(m[i, ]))))

planted_data <- function(n_regular, n_outliers, seed) {
  set.seed(seed)
  rotation <- qr.Q(qr(matrix(rnorm(16), 4, 4)))
  center <- c(1, 2, 3, 4)
  regular <- matrix(rnorm(n_regular * 4), n_regular, 4) %*% diag(c(3, 1.2, 0.7, 0.4)) %*% t(rotation)
  outliers <- matrix(rnorm(n_outliers * 4, sd = 0.3), n_outliers, 4) +
    matrix(10 * rotation[, 2], n_outliers, 4, byrow = TRUE)
  X <- sweep(rbind(regular, outliers), 2, center, "+")
  list(X = X, true_direction = rotation[, 1], outliers = n_regular + seq_len(n_outliers) - 1)
}

drawn_feature_matrices <- function() {
  # The feature matrices come from the project's own generator and feature code (Python); R only
  # fits them. Printed with repr (shortest round trip); the doubles R parses are stored with exact17.
  code <- paste(
    "import json",
    "from paperlib.datasets import categorization_cases",
    "from paperlib.arrangement import element_features",
    "from paperlib.arrangement.categorize import _appearance_matrix, unwrapped_orientation",
    "cases = categorization_cases('main', rng=0)",
    "out = {}",
    "for name in ('topology_2', 'crossings_top_row', 'mixed_5', 'control_single'):",
    "    ex = cases[name][1]",
    "    X, columns, _, _ = _appearance_matrix(element_features(ex.elements, ex.window.area), False)",
    "    X[:, 1] = unwrapped_orientation(X[:, 1])",
    "    out['drawn_' + name] = [[repr(float(v)) for v in row] for row in X]",
    "print(json.dumps(out))",
    sep = "\n"
  )
  rows <- jsonlite::fromJSON(paste(system2(".venv/bin/python", c("-c", shQuote(code)), stdout = TRUE), collapse = ""))
  lapply(rows, function(m) list(X = matrix(as.numeric(m), nrow = nrow(m))))
}

data(hbk, package = "robustbase")
data(starsCYG, package = "robustbase")
planted <- planted_data(60, 8, 20090801)
small <- planted_data(13, 2, 2009)
datasets <- list(
  planted = planted,
  small = small,
  hbk = list(X = as.matrix(hbk)),
  starsCYG = list(X = as.matrix(starsCYG))
)
datasets <- c(datasets, drawn_feature_matrices())

fit_json <- function(name, X, k, seed) {
  set.seed(seed)
  fit <- PcaHubert(X, k = k, alpha = 0.75, mcd = FALSE)
  list(
    data = name, k = k, alpha = 0.75, seed = seed, h = fit@quan,
    loadings = matrix_json(unclass(getLoadings(fit))),
    eigenvalues = unname(getEigenvalues(fit)),
    center = unname(getCenter(fit)),
    sd = unname(fit@sd), od = unname(fit@od),
    cutoff_sd = fit@cutoff.sd, cutoff_od = fit@cutoff.od,
    outliers = unname(which(!fit@flag)) - 1
  )
}

fits <- list()
for (name in names(datasets)) {
  X <- datasets[[name]]$X
  for (k in 1:2) for (seed in 1:5) fits[[length(fits) + 1]] <- fit_json(name, X, k, seed)
}

permutation_json <- function(name, X, k, i) {
  set.seed(100 + i)
  order <- sample(nrow(X))
  fit <- fit_json(name, X[order, , drop = FALSE], k, 1)
  list(data = name, k = k, order = order - 1, loadings = fit$loadings, eigenvalues = fit$eigenvalues,
       outliers = sort(order[fit$outliers + 1]) - 1)
}
permutations <- list()
for (name in c("planted", "hbk", "starsCYG", grep("^drawn_", names(datasets), value = TRUE))) {
  X <- datasets[[name]]$X
  for (k in 1:2) for (i in 1:20) permutations[[length(permutations) + 1]] <- permutation_json(name, X, k, i)
}

h_small <- h.alpha.n(0.75, nrow(small$X), 1)
outlyingness <- list(data = "small", h = h_small, values = rrcov:::outl(small$X, maxdir = 250, h = h_small))

unimcd_cases <- list(
  list(data = "hbk", column = 0, h = h.alpha.n(0.75, 75, 1)),
  list(data = "starsCYG", column = 1, h = h.alpha.n(0.75, 47, 1)),
  list(data = "planted", column = 2, h = h.alpha.n(0.75, 68, 1))
)
unimcd <- lapply(unimcd_cases, function(case) {
  m <- rrcov:::unimcd(datasets[[case$data]]$X[, case$column + 1], quan = case$h)
  c(case, list(location = m$tmcd, scale = m$smcd))
})

covmcd_json <- function(x) {
  set.seed(1)
  m <- covMcd(x, alpha = 0.75)
  list(
    h = m$quan, center = unname(m$center), scatter = matrix_json(as.matrix(m$cov)),
    raw_center = unname(m$raw.center), raw_scatter = matrix_json(as.matrix(m$raw.cov)),
    best = if (is.null(m$best)) NULL else sort(unname(m$best)) - 1
  )
}
covmcd <- list(
  starsCYG = covmcd_json(as.matrix(starsCYG)),
  starsCYG_column0 = covmcd_json(as.matrix(starsCYG)[, 1])
)

corrections <- list()
for (k in 1:4) for (n in c(10, 47, 200)) for (alpha in c(0.75, 0.9)) {
  corrections[[length(corrections) + 1]] <- list(
    k = k, n = n, alpha = alpha,
    raw = robustbase:::MCDcnp2(k, n, alpha), reweighted = robustbase:::MCDcnp2.rew(k, n, alpha)
  )
}

write_oracle(list(
  data = lapply(datasets, function(d) {
    out <- list(X = exact_rows(d$X))
    if (!is.null(d$true_direction)) out$true_direction <- exact17(d$true_direction)
    if (!is.null(d$outliers)) out$outliers <- d$outliers
    out
  }),
  fits = fits,
  permutations = permutations,
  outlyingness = outlyingness,
  unimcd = unimcd,
  covmcd = covmcd,
  corrections = corrections,
  rrcov_versions = list(rrcov = as.character(packageVersion("rrcov")),
                        robustbase = as.character(packageVersion("robustbase")))
), "tests/oracle/robpca.json")
