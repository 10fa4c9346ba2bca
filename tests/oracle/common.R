# Helpers shared by the oracle scripts: versions and JSON output.
oracle_versions <- function() {
  pkgs <- c("spatstat", "spatstat.geom", "spatstat.explore", "spatstat.model", "spatstat.random", "spatstat.data")
  c(list(R = R.version.string), setNames(lapply(pkgs, function(p) as.character(packageVersion(p))), pkgs))
}
# jsonlite writes at most 15 significant digits whatever `digits` says, so numbers do NOT
# reload as the same doubles. Oracle values compared with a tolerance are fine that way;
# where the exact double matters (coordinates and r grids on gridded data, where distances
# tie with r values), write it with exact17() as a "%.17g" string and parse it in the test.
exact17 <- function(x) sprintf("%.17g", x)
write_oracle <- function(value, file) {
  value$versions <- oracle_versions()
  writeLines(jsonlite::toJSON(value, digits = NA, auto_unbox = TRUE, na = "null", null = "null"), file)
  message("wrote ", file)
}
# a matrix as a list of its rows
matrix_json <- function(m) unname(lapply(seq_len(nrow(m)), function(i) unname(m[i, ])))

# Point patterns and fv tables as JSON, exactly: coordinates, windows and r values as 17-digit
# strings (ties between pair distances and r values decide counts), function values as numbers
# with VALUE_DIGITS significant digits (rounding error 5e-12 relative, far below the tests'
# tolerances), which keeps the files small.
VALUE_DIGITS <- 11

window_json <- function(W) {
  if (is.rectangle(W)) return(list(type = "rectangle", xrange = exact17(W$xrange), yrange = exact17(W$yrange)))
  stopifnot(is.polygonal(W))
  # spatstat: outer boundaries anticlockwise, holes clockwise
  list(type = "polygon", rings = lapply(W$bdry, function(ring) list(x = exact17(ring$x), y = exact17(ring$y))))
}

exact_pattern_json <- function(X) {
  out <- list(x = exact17(X$x), y = exact17(X$y), window = window_json(Window(X)))
  if (is.multitype(X)) {
    out$marks <- as.character(marks(X))
    out$categories <- levels(marks(X))
  }
  out
}

# an fv object as columns; `every` keeps rows 1, 1 + every, ... and always the last one
# (`extra`: further columns on the same r grid)
fv_json <- function(f, every = 1, extra = list()) {
  df <- c(as.list(as.data.frame(f)), extra)
  rows <- unique(c(seq(1, length(df$r), by = every), length(df$r)))
  out <- list(every = every, r = exact17(df$r[rows]))
  for (name in setdiff(names(df), c("r", "theo"))) out[[name]] <- signif(df[[name]][rows], VALUE_DIGITS)
  out
}
