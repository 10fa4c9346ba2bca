# spatstat fixtures for ppm(..., gamma_max = 1) in paperlib.pointprocess.fit: fits whose
# unconstrained gamma exceeds 1, and their projection onto 0 <= gamma <= 1 (Hurtut 2009, 3.1).
#
# Sourced by tests/oracle/spatstat_reference.R (run from the project root), or alone:
#   Rscript -e 'source("tests/oracle/common.R"); source("tests/oracle/spatstat_project.R")'
# Writes tests/oracle/project.json: the data (coordinates and window as 17-digit strings, so
# the tests need no R) and, per fit, spatstat's unconstrained fit and its projection.
#
# What spatstat does (spatstat.model 3.2-1, project.ppm / emend.ppm): an interaction declares
# which coefficients are valid. Strauss: gamma <= 1; MultiStraussHard: gamma <= 1 for pairs
# WITHOUT a hard core (with one, any finite gamma is valid, the density being integrable);
# StraussHard: any finite gamma. ppm(..., project = TRUE) refits an invalid model without its
# invalid terms (gamma = 1; Strauss becomes Poisson), keeping rbord, and with several invalid
# terms (spatstat.options(project.fast = FALSE), the default) tries removing each, recursively,
# and keeps the valid submodel of largest log pseudolikelihood.
#
# Hurtut's model requires gamma <= 1 with or without hard core. For the hard-core fits, where
# spatstat does not project, the reference is the same rule applied by brute force: the valid
# submodel (gamma <= 1 for all remaining terms) of largest log PL among all 2^k submodels that
# drop some interaction terms, i.e. fix their gamma at 1 (spatstat's Hardcore, MultiHard, or
# MultiStraussHard with the dropped pairs' shells emptied, see `submodel`), with rbord kept at
# the full model's reach. For a concave log PL this is the maximum subject to gamma <= 1 (the
# maximiser of the submodel whose terms are those not at the bound). The projected
# no-hard-core fits are checked against it too.
#
# Fits (radii off the data's 0.001 lattice: no pair distance equals a radius):
#   redwood     Strauss(r = 0.0805)                                 project = TRUE -> Poisson
#   redwood     StraussHard(r = 0.0805), hc estimated by spatstat    brute force -> Hardcore(hc)
#   matclust    rMatClust(12, 0.06, 8) in the unit square (seed 2009), Strauss(r = 0.05)
#   mixed       rMatClust(12, 0.06, 10) "clustered" + rSSI(0.06, 60) "regular" (seed 27):
#               MultiStraussHard(iradii, hradii = 0)                 project = TRUE
#               MultiStraussHard(iradii), hradii estimated           brute force
#   bramble01   bramblecanes, ages 0 and 1 (marks renamed age0, age1; the 6 points repeating a
#               location dropped), MultiStraussHard(
#               iradii = 0.0305, hradii = 0): all three gammas > 1   project = TRUE (recursion)
# Default quadrature (spatstat's nd) and the border correction throughout.
suppressPackageStartupMessages(library(spatstat))
source("tests/oracle/common.R")

# Coefficients that are NA (terms with an empty shell, see below) are left out; vcov is null
# where spatstat cannot compute it (it refuses models with NA coefficients).
# (I(): a single coefficient stays an array; 1 x 1 matrices do come out as [x])
coef_json <- function(fit) {
  estimated <- !is.na(coef(fit))
  variance <- function(...) tryCatch(matrix_json(vcov(fit, ...)), warning = function(w) NULL)
  list(
    interaction = if (is.null(fit$interaction)) "Poisson process" else fit$interaction$name,
    coef_names = I(names(coef(fit))[estimated]),
    coef = I(unname(coef(fit))[estimated]),
    vcov = variance(),
    vcov_hessian = variance(hessian = TRUE),
    logLik = as.numeric(logLik(fit, warn = FALSE)),
    n_fitted = sum(getglmsubset(fit))
  )
}

# (Hardcore and MultiHard name an interaction term that has no coefficient)
interaction_gammas <- function(fit) {
  coefs <- coef(fit)[intersect(fit$internal$Vnames, names(coef(fit)))]
  exp(coefs[!is.na(coefs)])
}

# The submodel without some interaction terms (gamma = 1), hard cores kept. A multitype pair
# is dropped by shrinking its shell to [h, h + 1e-12), which no pair distance falls in (its
# coefficient is then NA): spatstat's MultiStraussHard with iradii NA for a pair, as
# project.ppm builds it, drops that pair's hard core too (harmless there: it projects pairs
# without hard core only).
submodel <- function(iradii, hradii, drop) {
  if (all(drop)) {
    if (all(hradii == 0)) return(Poisson())
    return(if (nrow(hradii) == 1) Hardcore(hradii[1, 1]) else MultiHard(hradii = hradii))
  }
  if (nrow(iradii) == 1) {
    return(if (hradii[1, 1] > 0) StraussHard(r = iradii[1, 1], hc = hradii[1, 1]) else Strauss(iradii[1, 1]))
  }
  iradii[drop] <- ifelse(hradii[drop] > 0, hradii[drop] + 1e-12, NA)
  MultiStraussHard(iradii = iradii, hradii = hradii)
}

# all submodels dropping some interaction terms; the valid one (every gamma <= 1) of largest log PL
brute_force_projection <- function(X, trend, iradii, hradii, rbord) {
  pairs <- which(upper.tri(iradii, diag = TRUE), arr.ind = TRUE)
  best <- NULL
  for (k in 0:(2^nrow(pairs) - 1)) {
    drop <- matrix(FALSE, nrow(iradii), ncol(iradii))
    for (p in which(bitwAnd(k, 2^(seq_len(nrow(pairs)) - 1)) > 0)) drop[pairs[p, 1], pairs[p, 2]] <- drop[pairs[p, 2], pairs[p, 1]] <- TRUE
    # forcefit: a glm on the quadrature scheme, as project.ppm (not the exact Poisson MLE)
    fit <- ppm(X, trend, submodel(iradii, hradii, drop), rbord = rbord, forcefit = TRUE)
    if (all(interaction_gammas(fit) <= 1) && (is.null(best) || logLik(fit, warn = FALSE) > logLik(best, warn = FALSE))) {
      best <- fit
    }
  }
  best
}

set.seed(2009)
matclust <- rMatClust(kappa = 12, scale = 0.06, mu = 8)
set.seed(27)
mixed <- superimpose(clustered = rMatClust(kappa = 12, scale = 0.06, mu = 10), regular = rSSI(0.06, 60))
bramble01 <- bramblecanes[marks(bramblecanes) != "2"]
marks(bramble01) <- factor(marks(bramble01), levels = c("0", "1"), labels = c("age0", "age1"))
bramble01 <- bramble01[!duplicated(unmark(bramble01))]  # 6 points repeat a location: keep the first
data <- list(redwood = redwood, matclust = matclust, mixed = mixed, bramble01 = bramble01)

fits <- list()
add_fit <- function(name, data_name, model, full, projected, method, radii) {
  stopifnot(any(interaction_gammas(full) > 1))
  fits[[length(fits) + 1]] <<- c(list(name = name, data = data_name, model = model, method = method), radii,
                                 list(unconstrained = coef_json(full), projected = coef_json(projected)))
}
one <- function(x) matrix(x, 1, 1)

# monotype Strauss: spatstat's own projection (Poisson), checked against the brute force
r <- 0.0805
for (name in c("redwood", "matclust")) {
  X <- data[[name]]
  rr <- if (name == "redwood") r else 0.05
  full <- ppm(X ~ 1, Strauss(rr))
  projected <- ppm(X ~ 1, Strauss(rr), project = TRUE)
  stopifnot(isTRUE(projected$projected))
  brute <- brute_force_projection(X, ~1, one(rr), one(0), rbord = rr)
  stopifnot(isTRUE(all.equal(coef(projected), coef(brute))))
  add_fit(paste0(name, "_strauss"), name, "Strauss", full, projected, "project.ppm", list(r = rr, hc = 0))
}

# monotype StraussHard: spatstat keeps gamma > 1 (valid with a hard core); brute force -> Hardcore
full <- ppm(redwood ~ 1, StraussHard(r))
hc <- full$interaction$par$hc
brute <- brute_force_projection(redwood, ~1, one(r), one(hc), rbord = r)
add_fit("redwood_strausshard", "redwood", "StraussHard", full, brute, "brute force", list(r = r, hc = hc))

# multitype without hard cores: spatstat's projection (recursive search), checked against the brute force
mixed_iradii <- matrix(c(0.0525, 0.0425, 0.0425, 0.0925), 2, 2)
bramble_iradii <- matrix(0.0305, 2, 2)
for (case in list(list("mixed", mixed_iradii), list("bramble01", bramble_iradii))) {
  X <- data[[case[[1]]]]
  iradii <- case[[2]]
  none <- matrix(0, 2, 2)
  full <- ppm(X ~ marks, MultiStraussHard(iradii = iradii, hradii = none))
  projected <- ppm(X ~ marks, MultiStraussHard(iradii = iradii, hradii = none), project = TRUE)
  stopifnot(isTRUE(projected$projected))
  brute <- brute_force_projection(X, ~marks, iradii, none, rbord = max(iradii))
  stopifnot(isTRUE(all.equal(coef(projected), coef(brute))))
  add_fit(paste0(case[[1]], "_multistrauss"), case[[1]], "MultiStraussHard", full, projected, "project.ppm",
          list(iradii = matrix_json(iradii), hradii = matrix_json(none)))
}

# multitype with hard cores estimated by spatstat (Hurtut's model): brute force
full <- ppm(mixed ~ marks, MultiStraussHard(iradii = mixed_iradii))
hradii <- full$interaction$par$hradii
brute <- brute_force_projection(mixed, ~marks, mixed_iradii, hradii, rbord = max(mixed_iradii))
add_fit("mixed_multistrausshard", "mixed", "MultiStraussHard", full, brute, "brute force",
        list(iradii = matrix_json(mixed_iradii), hradii = matrix_json(unname(hradii))))

write_oracle(list(
  description = paste(
    "Fits with an unconstrained gamma > 1 and their projection onto gamma <= 1: spatstat's",
    "ppm(..., project = TRUE) (method 'project.ppm') where spatstat requires gamma <= 1, else the valid",
    "submodel of largest log pseudolikelihood among all submodels dropping interaction terms (method",
    "'brute force'). coef, vcov (Coeurjolly-Rubak), vcov_hessian, logLik as in ppm.json; spatstat's",
    "default quadrature, border correction."
  ),
  data = lapply(data, exact_pattern_json),
  fits = fits
), "tests/oracle/project.json")
