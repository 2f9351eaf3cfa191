# The concepts of the library and the layers they make (docs/architecture.md). One folder per concept under
# include/topple/ and src/; a concept may include (and call) only itself and the concepts below it, as listed here:
# TOPPLE_USES_<concept> names the concepts it builds on directly; what those build on is reachable too. The build
# checks every #include of include/topple/ and src/ against this table (cmake/CheckLayers.cmake) before it compiles
# anything, and each layer's library links only the layers below it, so an edge against the layers fails to build.
set(TOPPLE_CONCEPTS core numerics motion bodies solvers closed_forms survey ensemble inversion fragility region io
  output)

set(TOPPLE_USES_core "")                  # errors with their location, units, field tables, progress, output files
set(TOPPLE_USES_numerics core)            # root finding, step laws, DP5, log-sum-exp, normal cdf, cells, angles
set(TOPPLE_USES_motion numerics)          # ground motions, input grids, motion sets, RotD, spectra, synthesis
set(TOPPLE_USES_bodies motion)            # rocking bodies, mesh bodies and their resting pose
set(TOPPLE_USES_solvers bodies)           # sliding, 2-D sliding, flexible, rocking, slide-rock, oriented objects
set(TOPPLE_USES_closed_forms bodies)      # closed forms of rocking and of the thesis' pulses: oracles for the solvers
set(TOPPLE_USES_survey solvers)           # the observation model: outcomes, evidence, model choice, physics checks
set(TOPPLE_USES_ensemble solvers)         # plan, execute, store, MPI; sweeps
set(TOPPLE_USES_inversion survey ensemble)  # one pipeline (1 or 3 components), family, thresholds, likelihood
set(TOPPLE_USES_fragility ensemble)       # fragility curves and object spectra
set(TOPPLE_USES_region inversion)         # the regional fit, field, contours, survey-level entry point, MPI
set(TOPPLE_USES_io region fragility)      # readers only: records, surveys, sweeps, meshes
set(TOPPLE_USES_output io)                # writers: JSON, CSV, reports, plots, maps

# The libraries, one per layer, lowest first: a layer's library links the ones before it.
set(TOPPLE_LAYERS core physics analysis io output)
set(TOPPLE_LAYER_core core numerics)
set(TOPPLE_LAYER_physics motion bodies solvers closed_forms)
set(TOPPLE_LAYER_analysis survey ensemble inversion fragility region)
set(TOPPLE_LAYER_io io)
set(TOPPLE_LAYER_output output)
