# spatstat fixtures for paperlib.pointprocess.summary (Kest, Lest, Kcross, Lcross, pcf).
#
# Sourced by tests/oracle/spatstat_reference.R (run from the project root), or alone:
#   Rscript -e 'source("tests/oracle/common.R"); source("tests/oracle/spatstat_summary.R")'
# Writes tests/oracle/summary.json with, for each case, the point pattern (coordinates and
# window, so the tests need no R), spatstat's fv tables and timings of Lest, Kest, Lcross and pcf.
#
# With the environment variable SPATSTAT_SUMMARY_SERVE=1 it writes nothing and instead serves
# the timed calls (`benchmark_calls`) on standard input for benchmarks/bench_pointprocess_summary.py,
# which times spatstat in the same command as paperlib, on the same points (see serve_benchmark_calls).
#
# Exactness: coordinates, windows and r values must reload as the same doubles (ties between
# pair distances and r values decide the counts), but jsonlite writes at most 15 significant
# digits whatever `digits` says; so they are written as strings with 17 (`exact`), which the
# tests parse with float(). Function values are written as numbers with 11 significant
# digits (rounding error 5e-12 relative, far below the tests' 1e-8), which keeps the file
# to a few hundred KB. Tables on spatstat's default 513-value grid keep every
# row for cells (whose gridded coordinates put many pair distances exactly on r values) and
# every 2nd or 4th row elsewhere (`every`: rows 0, every, 2 every, ..., and the last). The
# `theo` columns (pi r^2, r, 1) are left out.
suppressPackageStartupMessages(library(spatstat))
source("tests/oracle/common.R")

all_corrections <- c("none", "border", "isotropic", "translate")

# r grids that no pair or boundary distance of the gridded data sets hits exactly
# (irrational step), so any tie rule gives the same counts
offgrid_r <- function(rmax) seq(0, rmax * (pi / 3.2), length.out = 101)
# an unevenly spaced grid: spatstat then uses its generic (histogram) code path
uneven_r <- function(rmax) rmax * ((0:60) / 60)^1.5

# Translation correction with the exact polygon overlap |W n (W + v)| (spatstat's Kest and
# Kmulti rasterise polygonal windows for it): the oracle for our exact polygon weights.
exact_trans_weights <- function(close, W) {
  edge.Trans(dx = close$dx, dy = close$dy, W = W, paired = TRUE, exact = TRUE)
}
exact_trans_K <- function(close, r, W, n_pairs) {
  breaks <- c(-(r[2] - r[1]), r)
  cumsum(whist(close$d, breaks, exact_trans_weights(close, W))) / (n_pairs / area(W))
}
# pcf.ppp's translation estimate (Epanechnikov kernel, Stoyan's rule, divisor r) with the
# exact polygon weights
exact_trans_pcf <- function(X, g) {
  n <- npoints(X)
  W <- Window(X)
  halfwidth <- 0.15 / sqrt(n / area(W))
  close <- closepairs(X, max(g$r) + halfwidth)
  density_args <- list(kernel = "epanechnikov", bw = halfwidth / sqrt(5), n = length(g$r), from = 0, to = max(g$r))
  spatstat.explore:::sewpcf(close$d, exact_trans_weights(close, W), density_args, n * (n - 1) / area(W), "r")$g
}

summary_cases <- function() {
  out <- list()
  for (name in c("cells", "redwood", "swedishpines")) {
    X <- get(name)
    K <- Kest(X, correction = all_corrections)
    rmax <- max(K$r)
    out[[name]] <- list(
      pattern = exact_pattern_json(X),
      Kest = fv_json(K, every = if (name == "cells") 1 else 2),
      Lest_offgrid = fv_json(Lest(X, r = offgrid_r(rmax), correction = all_corrections)),
      Kest_uneven = fv_json(Kest(X, r = uneven_r(rmax), correction = all_corrections)),
      Kest_border_only = fv_json(Kest(X, correction = "border"), every = 4)
    )
  }
  A <- amacrine
  cross <- list(pattern = exact_pattern_json(A))
  for (pair in list(c("on", "off"), c("off", "on"), c("on", "on"))) {
    key <- paste(pair, collapse = "_")
    K <- Kcross(A, pair[1], pair[2], correction = all_corrections)
    cross[[paste0("Kcross_", key)]] <- fv_json(K, every = 2)
    cross[[paste0("Lcross_offgrid_", key)]] <- fv_json(
      Lcross(A, pair[1], pair[2], r = offgrid_r(max(K$r)), correction = all_corrections)
    )
  }
  out$amacrine <- cross
  # A lattice in a window away from the origin: Krect first moves the window to the origin,
  # which changes the last bit of some distances and so which r values they tie with
  # (here r = 0.125 and r = rmax = 0.25).
  g <- expand.grid(i = 0:7, j = 0:7)
  X <- ppp(g$i * 0.125 + 0.1 + 0.0625, g$j * 0.125 + 0.2 + 0.0625, window = owin(c(0.1, 1.1), c(0.2, 1.2)))
  out$lattice <- list(pattern = exact_pattern_json(X), Kest = fv_json(Kest(X, correction = all_corrections), every = 2))
  out
}

polygon_case <- function() {
  set.seed(20240517)
  X <- runifpoint(100, letterR)
  marks(X) <- factor(sample(c("a", "b"), npoints(X), replace = TRUE))
  Y <- unmark(X)
  W <- Window(X)
  K <- Kest(Y, correction = all_corrections)
  r <- K$r
  Kab <- Kcross(X, "a", "b", correction = all_corrections)
  Xa <- X[marks(X) == "a"]
  Xb <- X[marks(X) == "b"]
  g <- pcf(Y)
  list(
    pattern = exact_pattern_json(X),
    Kest = fv_json(K, every = 2, extra = list(
      trans_exact = exact_trans_K(closepairs(Y, max(r)), r, W, npoints(Y) * (npoints(Y) - 1))
    )),
    Kest_border_only = fv_json(Kest(Y, correction = "border"), every = 4),
    Kcross_a_b = fv_json(Kab, every = 2, extra = list(
      trans_exact = exact_trans_K(crosspairs(Xa, Xb, max(Kab$r)), Kab$r, W, npoints(Xa) * npoints(Xb))
    )),
    pcf = fv_json(g, every = 4, extra = list(trans_exact = exact_trans_pcf(Y, g))),
    geometry = list(boundingradius = boundingradius(W), diameter = diameter(W), rmax_trans = rmax.Trans(W))
  )
}

pcf_cases <- function() {
  out <- list()
  for (name in c("cells", "redwood", "swedishpines")) {
    X <- get(name)
    divisor <- if (name == "swedishpines") "d" else "r"
    g <- pcf(X, correction = c("none", "translate", "isotropic"), divisor = divisor)
    # With divisor "r", spatstat's pcf "un" column is a density normalised to total mass 1
    # (sewpcf passes a weight of length 1 to unnormdensity), i.e. the uncorrected estimate
    # divided by the number of ordered pairs closer than rmax + the kernel half-width,
    # recorded here. (With divisor "d" the weights become 1/d and the column is right.)
    lambda <- npoints(X) / area(Window(X))
    halfwidth <- 0.15 / sqrt(lambda)
    out[[name]] <- list(
      divisor = divisor,
      table = fv_json(g, every = 4),
      bw = attr(g, "bw"),
      un_pairs = length(closepairs(X, max(g$r) + halfwidth, what = "ijd")$d)
    )
  }
  out
}

# median over `repeats` of the mean time of `calls` consecutive calls (system.time counts milliseconds:
# a call of a few ms is timed in a batch)
median_seconds <- function(expr_fun, repeats, calls = 1) {
  expr_fun()  # warm-up
  median(replicate(repeats, system.time(for (i in seq_len(calls)) expr_fun())[["elapsed"]])) / calls
}

# The calls timed here and by the benchmark, on n uniform points in the unit square with marks
# a, b, a, b, ... (for Lcross), spatstat's default r grid and defaults otherwise:
# Lest/Kest rmax 0.25 at 1e3, 0.178 at 1e4, 0.0564 at 1e5; Lcross("a", "b") rmax from the
# intensity of b: 0.25, 0.25, 0.0798; pcf translate + Ripley, Epanechnikov kernel, Stoyan's
# rule (0.15), divisor r.
benchmark_calls <- list(
  Lest_isotropic = function(X) Lest(X, correction = "isotropic"),
  Lest_border = function(X) Lest(X, correction = "border"),
  Kest_isotropic = function(X) Kest(X, correction = "isotropic"),
  Lcross_isotropic = function(X) Lcross(X, "a", "b", correction = "isotropic"),
  pcf_default = function(X) pcf(X)
)
alternating_marks <- function(n) factor(c("a", "b")[(seq_len(n) - 1) %% 2 + 1], levels = c("a", "b"))

# Timings of benchmark_calls on runifpoint(n) (seed 1; pcf not at 1e5); at 1e3 and 1e4 also Lest with rmax = 0.05,
# the setting of the conventions notes' table. Keys as benchmark_calls' names without "Lest_"
# for Lest (isotropic, border), as recorded before the others were added.
lest_timings <- function() {
  out <- list()
  for (n in c(1e3, 1e4, 1e5)) {
    set.seed(1)
    X <- runifpoint(n)
    marks(X) <- alternating_marks(n)
    Y <- unmark(X)
    repeats <- if (n < 1e5) 7 else 3
    calls <- if (n < 1e4) 50 else 1
    timing <- list()
    for (name in names(benchmark_calls)) {
      # pcf.ppp spends most of its time in deparse() (of the pair weights, through density's call):
      # 0.4 s at 1e3 points, 24 s at 1e4 on a quiet machine (1e7 pairs; one call at a time, 3 repeats;
      # 2.5 minutes under load), ten times the pairs at 1e5 (not timed)
      if (name == "pcf_default" && n >= 1e5) next
      key <- sub("^Lest_", "", name)
      data <- if (name == "Lcross_isotropic") X else Y
      slow <- name == "pcf_default"
      timing[[key]] <- median_seconds(function() benchmark_calls[[name]](data), if (slow) 3 else repeats,
                                      if (slow) 1 else calls)
    }
    if (n < 1e5) {
      timing$isotropic_rmax_0.05 <- median_seconds(function() Lest(Y, rmax = 0.05, correction = "isotropic"),
                                                   repeats, calls)
      timing$border_rmax_0.05 <- median_seconds(function() Lest(Y, rmax = 0.05, correction = "border"),
                                                repeats, calls)
    }
    out[[format(n, scientific = FALSE)]] <- timing
  }
  out
}

# A line protocol on standard input, one reply line each on standard output:
#   load PATH N     -> X: N points read from PATH (2N float64, x then y), unit square, marks a, b, a, ...
#   run NAME        -> call benchmark_calls[[NAME]] on X (the caller times the round trip)
#   values NAME PATH -> the call's fv table written to PATH as float64, column by column; reply
#                       "ok" and the column names
#   quit
# Replies "ok ..." or "error MESSAGE".
serve_benchmark_calls <- function() {
  input <- file("stdin")
  open(input)
  X <- Y <- NULL
  reply <- function(...) {
    cat(..., "\n", sep = "")
    flush(stdout())
  }
  repeat {
    line <- readLines(input, n = 1)
    if (length(line) == 0 || line == "quit") break
    words <- strsplit(line, " ", fixed = TRUE)[[1]]
    result <- tryCatch({
      if (words[1] == "load") {
        n <- as.integer(words[3])
        xy <- readBin(words[2], "double", n = 2 * n)
        X <- ppp(xy[seq_len(n)], xy[n + seq_len(n)], window = square(1), marks = alternating_marks(n))
        Y <- unmark(X)
        "ok"
      } else {
        data <- if (words[2] == "Lcross_isotropic") X else Y
        f <- benchmark_calls[[words[2]]](data)
        if (words[1] == "values") {
          table <- as.data.frame(f)
          writeBin(as.numeric(unlist(table, use.names = FALSE)), words[3])
          paste("ok", paste(names(table), collapse = " "))
        } else {
          "ok"
        }
      }
    }, error = function(e) paste("error", conditionMessage(e)))
    reply(result)
  }
}

if (Sys.getenv("SPATSTAT_SUMMARY_SERVE") == "1") {
  serve_benchmark_calls()
} else {
  write_oracle(
    list(
      description = paste(
        "spatstat Kest/Lest/Kcross/Lcross/pcf on its data sets and a letterR polygon case;",
        "function values rounded to 11 significant digits; timings are median elapsed seconds",
        "of Lest (isotropic, border), Kest (isotropic: Kest_isotropic), Lcross a to b",
        "(isotropic: Lcross_isotropic) and pcf (defaults: pcf_default) on uniform points in the",
        "unit square with alternating marks a, b (spatstat's default r grid unless named)"
      ),
      datasets = summary_cases(),
      polygon = polygon_case(),
      pcf = pcf_cases(),
      timings = lest_timings()
    ),
    "tests/oracle/summary.json"
  )
}
