# -mode fe2_static (src/modes/fe2_static_run.cpp): static equilibrium of the coarse model with load
# stepping, both quadrature rules (-coarse_quadrature sri|full).
#
# The cantilever (config/cantilever_static.yaml) at a small load, 16 x 4 elements, against an
# independent linear-elastic Q1 implementation in numpy (bench/cantilever_reference.py) with each
# rule: the neo-Hookean solve differs from the linear one by O(load^2) (5e-9 at deflection/length
# 1e-4; the beam's mirror symmetry removes the O(load) term).
set(STATIC $<TARGET_FILE:turgor_app> -mode fe2_static -output_overwrite)
set(STATIC_NH -material neo_hookean -nh_mu 0.38461538461538464 -nh_lambda 0.57692307692307687 -nh_density 1 -nh_viscosity 0)
set(STATIC_BEAM -coarse_dm_plex_simplex 0 -coarse_dm_plex_box_faces 16,4 -coarse_dm_plex_box_upper 400,100 -coarse_dirichlet_values 4)
set(REFERENCE ${PROJECT_SOURCE_DIR}/bench/cantilever_reference.py --faces 16,4 --g=-1e-8)
foreach(rule sri full)
  turgor_add_test(fe2_static_cantilever_${rule} COMMAND ${STATIC} ${STATIC_NH} ${STATIC_BEAM} -coarse_quadrature ${rule} -body_force 0,-1e-8
    -output_dir static_cantilever_${rule} LABELS fe2 static TIMEOUT 60 SETUP static_cantilever_${rule})
  turgor_add_test(fe2_static_cantilever_${rule}_reference COMMAND ${REFERENCE} --rule ${rule} --check static_cantilever_${rule} --rtol 1e-7
    LABELS fe2 static TIMEOUT 60 REQUIRES static_cantilever_${rule})
endforeach()
# Q2 (-coarse_element q2) on 8 x 2 elements against the numpy reference's own 9-node elements (both
# rules: deviator at 3 x 3 Gauss points, pressure at 2 x 2 for sri): measured 5e-9 (the neo-Hookean
# solve's O(load^2))
set(STATIC_BEAM_Q2 -coarse_dm_plex_simplex 0 -coarse_dm_plex_box_faces 8,2 -coarse_dm_plex_box_upper 400,100 -coarse_dirichlet_values 4 -coarse_element q2)
foreach(rule sri full)
  turgor_add_test(fe2_static_cantilever_q2_${rule} COMMAND ${STATIC} ${STATIC_NH} ${STATIC_BEAM_Q2} -coarse_quadrature ${rule} -body_force 0,-1e-8
    -output_dir static_cantilever_q2_${rule} LABELS fe2 static TIMEOUT 60 SETUP static_cantilever_q2_${rule})
  turgor_add_test(fe2_static_cantilever_q2_${rule}_reference COMMAND ${PROJECT_SOURCE_DIR}/bench/cantilever_reference.py --faces 8,2 --g=-1e-8
    --element q2 --rule ${rule} --check static_cantilever_q2_${rule} --rtol 1e-7 LABELS fe2 static TIMEOUT 60 REQUIRES static_cantilever_q2_${rule})
endforeach()
# the body force along the beam: the tip's horizontal displacement against the same reference (no
# mirror symmetry removes the O(load) nonlinearity here: at g = 1e-8 the two differ by 2e-6)
turgor_add_test(fe2_static_axial_q2 COMMAND ${STATIC} ${STATIC_NH} ${STATIC_BEAM_Q2} -body_force 1e-10,0 -output_dir static_axial_q2 LABELS fe2 static
  TIMEOUT 60 SETUP static_axial_q2)
turgor_add_test(fe2_static_axial_q2_reference COMMAND ${PROJECT_SOURCE_DIR}/bench/cantilever_reference.py --faces 8,2 --g=1e-10 --element q2 --rule sri
  --axial --check static_axial_q2 --rtol 1e-7 LABELS fe2 static TIMEOUT 60 REQUIRES static_axial_q2)
# a membrane along the top and bottom faces (-coarse_skin_stiffness EA = 20: 6 EA / (E H) = 1.2, the
# deflection about halved), bent and stretched, Q2 and Q1 and on 2 ranks, against the numpy
# reference's own membrane elements: measured 1.2e-9 bent, 9.7e-9 stretched
set(SKIN -coarse_skin_stiffness 20)
turgor_add_test(fe2_static_skin_q2 COMMAND ${STATIC} ${STATIC_NH} ${STATIC_BEAM_Q2} ${SKIN} -body_force 0,-1e-8 -output_dir static_skin_q2 LABELS fe2 static
  TIMEOUT 60 SETUP static_skin_q2)
turgor_add_test(fe2_static_skin_q2_reference COMMAND ${PROJECT_SOURCE_DIR}/bench/cantilever_reference.py --faces 8,2 --g=-1e-8 --element q2 --rule sri
  --skin 20 --check static_skin_q2 --rtol 1e-7 LABELS fe2 static TIMEOUT 60 REQUIRES static_skin_q2)
turgor_add_test(fe2_static_skin_axial_q2 COMMAND ${STATIC} ${STATIC_NH} ${STATIC_BEAM_Q2} ${SKIN} -body_force 1e-10,0 -output_dir static_skin_axial_q2 LABELS fe2
  static TIMEOUT 60 SETUP static_skin_axial_q2)
turgor_add_test(fe2_static_skin_axial_q2_reference COMMAND ${PROJECT_SOURCE_DIR}/bench/cantilever_reference.py --faces 8,2 --g=1e-10 --element q2 --rule sri
  --skin 20 --axial --check static_skin_axial_q2 --rtol 1e-7 LABELS fe2 static TIMEOUT 60 REQUIRES static_skin_axial_q2)
turgor_add_test(fe2_static_skin_q1 COMMAND ${STATIC} ${STATIC_NH} ${STATIC_BEAM} ${SKIN} -body_force 0,-1e-8 -output_dir static_skin_q1 LABELS fe2 static
  TIMEOUT 60 SETUP static_skin_q1)
turgor_add_test(fe2_static_skin_q1_reference COMMAND ${REFERENCE} --rule sri --skin 20 --check static_skin_q1 --rtol 1e-7 LABELS fe2 static TIMEOUT 60
  REQUIRES static_skin_q1)
turgor_add_test(fe2_static_skin_q2_np2 COMMAND ${MPIEXEC_ROOT} -n 2 ${STATIC} ${STATIC_NH} ${STATIC_BEAM_Q2} ${SKIN} -body_force 0,-1e-8
  -output_dir static_skin_q2_np2 LABELS fe2 static mpi TIMEOUT 60 SETUP static_skin_q2_np2)
turgor_add_test(fe2_static_skin_q2_np2_reference COMMAND ${PROJECT_SOURCE_DIR}/bench/cantilever_reference.py --faces 8,2 --g=-1e-8 --element q2 --rule sri
  --skin 20 --check static_skin_q2_np2 --rtol 1e-7 LABELS fe2 static mpi TIMEOUT 60 REQUIRES static_skin_q2_np2)
turgor_add_test(fe2_static_summary COMMAND ${CHECK} keys static_cantilever_sri mode status material element quadrature n_elements n_material_points
  load_factor_final load_increments load_cutbacks snes_its ksp_its rhs_evals jacobian_evals material_evaluations tip_displacement_final wall_time_s
  rve_solves snapshots LABELS fe2 static REQUIRES static_cantilever_sri)
turgor_add_test(fe2_static_xdmf COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/check_xdmf.py static_cantilever_full/coarse.xmf LABELS fe2 static
  REQUIRES static_cantilever_full)
# the scene file runs (32 x 8, deflection/length 1e-3)
turgor_add_test(fe2_static_scene COMMAND $<TARGET_FILE:turgor_app> -options_file_yaml ${PROJECT_SOURCE_DIR}/config/cantilever_static.yaml
  -output_dir static_scene -output_overwrite LABELS fe2 static TIMEOUT 60 PASS_REGEX "Done: load factor 1")

# The static answer is the long-time limit of the time-dependent run: neo-Hookean on the default
# 2 x 2 box under the default body force, overdamped (eta = 1000) and run to 300 µs by -mode fe2.
set(STATIC_BOX2 -coarse_dm_plex_simplex 0 -coarse_dm_plex_box_faces 2,2 -coarse_dm_plex_box_upper 400,400 -material neo_hookean)
turgor_add_test(fe2_static_nh_box COMMAND ${STATIC} ${STATIC_BOX2} -output_dir static_nh_box LABELS fe2 static TIMEOUT 60 SETUP static_nh_box)
turgor_add_test(fe2_static_nh_box_dynamic COMMAND $<TARGET_FILE:turgor_app> -mode fe2 ${STATIC_BOX2} -nh_viscosity 1000 -ts_max_time 300
  -fe2_snapshots 0 -fe2_progress_interval 0 -output_dir static_nh_box_dynamic -output_overwrite LABELS fe2 static TIMEOUT 60 SETUP static_nh_box_dynamic)
turgor_add_test(fe2_static_is_long_time_limit COMMAND ${CHECK} final static_nh_box_dynamic static_nh_box 1e-7 LABELS fe2 static
  REQUIRES "static_nh_box;static_nh_box_dynamic")

# The RVE material at the scene's load on the 2 x 2 box (20 RVEs, whose stress at rest deforms the
# tissue before any load: the load factor 0 solve), on 1 and 2 ranks; the seed's Psi-tc tolerance,
# so that the comparison sees the decomposition rather than the RVEs' convergence noise.
set(STATIC_RVE -coarse_dm_plex_simplex 0 -coarse_dm_plex_box_faces 2,2 -coarse_dm_plex_box_upper 400,400 -rve_psi_atol 1e-12 -rve_psi_steptol 1e-12
  -mode fe2_static -output_overwrite)
turgor_add_test(fe2_static_rve_np1 COMMAND ${MPIEXEC_ROOT} -n 1 $<TARGET_FILE:turgor_app> ${STATIC_RVE} -output_dir static_rve_np1 LABELS fe2 static rve mpi
  TIMEOUT 60 SETUP static_rve_np1)
turgor_add_test(fe2_static_rve_np2 COMMAND ${MPIEXEC_ROOT} -n 2 $<TARGET_FILE:turgor_app> ${STATIC_RVE} -output_dir static_rve_np2 LABELS fe2 static rve mpi
  TIMEOUT 60 SETUP static_rve_np2)
turgor_add_test(fe2_static_rve_ranks_agree COMMAND ${CHECK} tip static_rve_np1 static_rve_np2 1e-9 LABELS fe2 static rve mpi
  REQUIRES "static_rve_np1;static_rve_np2")
# 2 ranks with the neo-Hookean cantilever (full rule) give 1 rank's answer
turgor_add_test(fe2_static_np2 COMMAND ${MPIEXEC_ROOT} -n 2 ${STATIC} ${STATIC_NH} ${STATIC_BEAM} -coarse_quadrature full -body_force 0,-1e-8
  -output_dir static_cantilever_np2 LABELS fe2 static mpi TIMEOUT 60 SETUP static_cantilever_np2)
turgor_add_test(fe2_static_ranks_agree COMMAND ${CHECK} tip static_cantilever_np2 static_cantilever_full 1e-12 LABELS fe2 static mpi
  REQUIRES "static_cantilever_np2;static_cantilever_full")

# Load cut-back: at a body force of 2e-4 the whole load in one Newton solve inverts elements (the
# material points fail), the increment is halved and the run goes on; the answer is that of 40 small
# increments (tip -348, deflection/length 0.87).
turgor_add_test(fe2_static_cutback COMMAND ${STATIC} ${STATIC_NH} ${STATIC_BEAM} -body_force 0,-2e-4 -output_dir static_cutback
  LABELS fe2 static hard TIMEOUT 60 SETUP static_cutback)
turgor_add_test(fe2_static_small_increments COMMAND ${STATIC} ${STATIC_NH} ${STATIC_BEAM} -body_force 0,-2e-4 -fe2_static_load_steps 40
  -output_dir static_small_increments LABELS fe2 static hard TIMEOUT 60 SETUP static_small_increments)
turgor_add_test(fe2_static_cutback_counted COMMAND ${CHECK} positive static_cutback load_cutbacks LABELS fe2 static hard REQUIRES static_cutback)
turgor_add_test(fe2_static_cutback_material_failures COMMAND ${CHECK} positive static_cutback material_failures LABELS fe2 static hard
  REQUIRES static_cutback)
turgor_add_test(fe2_static_cutback_agrees COMMAND ${CHECK} final static_cutback static_small_increments 1e-7 LABELS fe2 static hard
  REQUIRES "static_cutback;static_small_increments")
# below -fe2_static_min_increment the run fails cleanly, naming the load factor it reached (Newton
# limited to 4 iterations: 0.125 converges, 0.25 does not, and half its increment is below 0.1)
turgor_add_test(fe2_static_min_increment_reached COMMAND ${BAD} "reached load factor 0.125 of 1 .*-fe2_static_min_increment = 0.1"
  ${STATIC} ${STATIC_NH} ${STATIC_BEAM} -body_force 0,-1e-4 -fe2_static_load_steps 4 -fe2_static_snes_max_it 4 -fe2_static_min_increment 0.1
  -output_dir static_min_increment LABELS fe2 static hard TIMEOUT 60)

# Bad input of this mode: tests/bad_input.txt (section fe2_static).

# A rank with no element (2 elements on 3 ranks; METIS refuses more ranks than elements, PETSc's
# default partitioner leaves one empty) or whose material points another rank's group evaluates (2
# ranks, METIS): the same load path as one rank (Newton converges with the same tangent).
set(STATIC_EMPTY ${STATIC_NH} -coarse_dm_plex_simplex 0 -coarse_dm_plex_box_upper 400,400 -coarse_dm_plex_box_faces 2,1)
foreach(case "1;-coarse_partitioner;metis" "2;-coarse_partitioner;metis" "3")
  list(POP_FRONT case np)
  set(partitioner ${case})
  turgor_add_test(fe2_static_empty_np${np} COMMAND ${MPIEXEC_ROOT} -n ${np} ${STATIC} ${STATIC_EMPTY} ${partitioner} -output_dir static_empty_np${np}
    LABELS fe2 static mpi TIMEOUT 60 SETUP static_empty_np${np})
endforeach()
foreach(np 2 3)
  turgor_add_test(fe2_static_empty_np${np}_agree COMMAND ${CHECK} tip static_empty_np${np} static_empty_np1 1e-9 LABELS fe2 static mpi
    REQUIRES "static_empty_np1;static_empty_np${np}")
endforeach()
