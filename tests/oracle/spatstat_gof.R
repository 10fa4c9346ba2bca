# spatstat fixtures for paperlib.pointprocess.gof (dclf.test, mad.test).
#
# Sourced by tests/oracle/spatstat_reference.R (run from the project root), or alone:
#   Rscript -e 'source("tests/oracle/common.R"); source("tests/oracle/spatstat_gof.R")'
# Writes tests/oracle/gof.json. Randomness is kept out of the comparison: the simulated
# patterns are drawn here once, written into the fixture (17-digit coordinates), and given to
# spatstat as `simulate = <list of patterns>`; the tests give the same list to dclf_test and
# mad_test. For each case: the observed pattern, the simulations, and per test variant
# spatstat's statistic, p-value, r interval and the statistic of every simulation.
#
# Cases:
#   redwood_csr     redwood against 39 binomial patterns (runifpoint(62)), Lest, isotropic;
#                   variants: spatstat's defaults, use.theory, leaveout 0 and 2, one-sided
#                   alternatives (clamped or not), an rinterval
#   cells_strauss   cells against 19 simulations of its fitted Strauss(0.1) model
#                   (simulate.ppm, i.e. rmh), Kest, border correction
#   amacrine_cross  amacrine against 19 random relabellings (rlabel), Lcross(on, off), translate
#   binomial_csr    a binomial pattern against the same 39, Lest (a p-value inside (0, 1))
#   redwood_pcf     redwood against the 39 binomial patterns, pcf (isotropic): infinite at r = 0,
#                   so spatstat starts the r interval at the next r
# tie.rule = "mean" (no ties occur; spatstat's default would draw a random number if they did).
suppressPackageStartupMessages(library(spatstat))
source("tests/oracle/common.R")

# rlabel's patterns keep the coordinates: their marks only
marks_json <- function(X) list(marks = as.character(marks(X)), categories = levels(marks(X)))

test_json <- function(test, args) {
  info <- attr(test, "info")
  stats <- attr(test, "statistics")
  list(
    args = if (length(args)) args else NULL,
    statistic = unname(stats$data),
    p_value = test$p.value,
    rinterval = attr(test, "rinterval"),
    simulated = I(unname(stats$sim)),
    leaveout = info$leaveout,
    use_theory = info$use.theo,
    nties = info$nties
  )
}

# dclf.test and mad.test for every variant (a list of extra arguments)
run_tests <- function(X, fun, sims, funargs, variants) {
  out <- list()
  for (args in variants) {
    for (test in c("dclf", "mad")) {
      f <- if (test == "dclf") dclf.test else mad.test
      result <- do.call(f, c(list(X, fun, simulate = sims, nsim = length(sims), savefuns = TRUE, verbose = FALSE,
                                  tie.rule = "mean"), funargs, args))
      out[[length(out) + 1]] <- c(list(test = test), test_json(result, args))
    }
  }
  out
}

simulations <- list()
cases <- list()
add_case <- function(name, X, simulation, fun, funargs, variants) {
  message(name)
  cases[[length(cases) + 1]] <<- list(
    name = name, fun = fun, funargs = funargs, observed = exact_pattern_json(X), simulations = simulation,
    tests = run_tests(X, get(fun), simulations[[simulation]]$patterns, funargs, variants)
  )
}
add_simulations <- function(name, patterns) simulations[[name]] <<- list(patterns = patterns)
simulations_json <- function() {
  lapply(simulations, function(s) lapply(s$patterns, if (isTRUE(s$coordinates)) exact_pattern_json else marks_json))
}

set.seed(42)
add_simulations("binomial62", lapply(1:39, function(i) runifpoint(npoints(redwood), Window(redwood))))
set.seed(43)
add_simulations("cells_strauss", unname(as.list(simulate(ppm(cells ~ 1, Strauss(0.1)), nsim = 19, progress = FALSE))))
set.seed(44)
add_simulations("amacrine_rlabel", lapply(1:19, function(i) rlabel(amacrine)))
simulations$binomial62$coordinates <- simulations$cells_strauss$coordinates <- TRUE

add_case("redwood_csr", redwood, "binomial62", "Lest", list(correction = "isotropic"), list(
  list(),
  list(use.theory = TRUE),
  list(leaveout = 0),
  list(leaveout = 2),
  list(alternative = "less"),
  list(alternative = "greater", clamp = TRUE),
  list(rinterval = c(0.01, 0.1))
))
set.seed(45)
add_case("binomial_csr", runifpoint(npoints(redwood), Window(redwood)), "binomial62", "Lest",
         list(correction = "isotropic"), list(list(), list(use.theory = TRUE)))
add_case("cells_strauss", cells, "cells_strauss", "Kest", list(correction = "border"), list(list()))
add_case("amacrine_cross", amacrine, "amacrine_rlabel", "Lcross", list(i = "on", j = "off", correction = "translate"),
         list(list(), list(use.theory = TRUE)))
add_case("redwood_pcf", redwood, "binomial62", "pcf", list(correction = "isotropic"), list(list()))

write_oracle(list(
  description = paste(
    "spatstat dclf.test and mad.test with simulate = <list of the patterns in the fixture>: statistic (u or mad),",
    "p_value, rinterval, simulated = attr(, 'statistics')$sim, leaveout and use_theory actually used;",
    "simulations: the patterns by name, each case naming its own; amacrine_rlabel carries marks only (rlabel",
    "keeps amacrine's coordinates)."
  ),
  simulations = simulations_json(),
  cases = cases
), "tests/oracle/gof.json")
