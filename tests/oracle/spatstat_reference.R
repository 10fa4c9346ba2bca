# Regenerates the spatstat oracle fixtures in tests/oracle/*.json.
#
#   Rscript tests/oracle/spatstat_reference.R        (from the project root)
#
# Needs R with spatstat and jsonlite (Debian: r-base-core r-cran-spatstat
# r-cran-spatstat.data r-cran-spatstat.model r-cran-spatstat.random
# r-cran-spatstat.explore r-cran-spatstat.geom r-cran-jsonlite). The tests read the JSON
# files and never need R. Each part below writes its own fixture file, with the versions
# of R and the spatstat packages recorded in it.
suppressPackageStartupMessages({
  library(spatstat)
  library(jsonlite)
})
here <- "tests/oracle"
for (part in c("spatstat_summary.R", "spatstat_ppm.R", "spatstat_rmh.R", "spatstat_project.R", "spatstat_gof.R",
               "spatstat_duplicates.R")) {
  message("running ", part)
  source(file.path(here, part), local = new.env())
}
