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
