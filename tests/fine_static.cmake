# -mode fine_static: the static equilibrium of a polygonal tissue at the scene's load times.

# The gripped, turgid tissue of config/voronoi_tangent_fine.yaml on 16 cells (100 x 100 µm): its
# equilibria at t = 25 (held, inflated) and t = 30 µs (stretched by 0.1 µm) against the same scene
# run dynamically to t = 60 µs (settled by its viscosity and dashpots: the last row's forces are
# steady to 1e-9). Their groups.csv rows (every grip's displacement and reaction) agree to 1e-8 of
# the largest reaction.
set(STATIC_GRIPS -options_file_yaml ${PROJECT_SOURCE_DIR}/config/voronoi_tangent_fine.yaml -tissue_voronoi_cells 16 -tissue_box 0,0,100,100
  -control_left_box -1,-1,12.5,101 -control_right_box 87.5,-1,101,101 -control_bottom_box 12.5,-1,87.5,12.5 -control_top_box 12.5,87.5,87.5,101
  -output_overwrite)
turgor_add_test(fine_static_grips COMMAND turgor_app ${STATIC_GRIPS} -mode fine_static -fine_static_times 25,30 -output_dir static_grips LABELS fine
  SETUP static_grips)
turgor_add_test(fine_static_grips_dynamic COMMAND turgor_app ${STATIC_GRIPS} -fine_snapshots 0 -fine_progress_interval 0 -output_dir static_grips_dyn
  LABELS fine SETUP static_grips_dyn)
turgor_add_test(fine_static_vs_dynamic COMMAND ${CHECK} csvrow static_grips/groups.csv 1 static_grips_dyn/groups.csv -1 1e-8 LABELS fine
  REQUIRES "static_grips;static_grips_dyn")
# ... and on two ranks (rank 1 holds no particle: an empty rank joins every solve): the same reactions
# and displacements, to the solve's own accuracy (|R| <= 1e-12 k_b L: the displacements to about 1e-8
# of themselves; MUMPS orders the sums of its factorisation by the ranks, so the last iterates differ)
turgor_add_test(fine_static_grips_np2 COMMAND ${MPIEXEC_ROOT} -n 2 $<TARGET_FILE:turgor_app> ${STATIC_GRIPS} -mode fine_static -fine_static_times 25,30
  -output_dir static_grips_np2 LABELS fine mpi SETUP static_grips_np2)
turgor_add_test(fine_static_np2_agree COMMAND ${CHECK} csvrel static_grips static_grips_np2 groups.csv 1e-6 LABELS fine mpi
  REQUIRES "static_grips;static_grips_np2")

# A cantilever chain of hinges (config/polygon_cantilever.yaml: 101 nodes over 1 µm, k_r = 2e5 µN µm,
# root held) under a tip force F = 0.01 µN: the hinge at x_i turns by F (L - x_i) / k_r, so the tip
# deflects by F / k_r sum (L - x_i)^2 = 0.01 / 2e5 x 32.835 = 1.64175e-6 µm (geometric nonlinearity
# (d / L)^2 ~ 3e-12); the root's reaction is the tip force. The bars' stiffness sets the force scale
# (k_b L = 1e7 µN, against a load of 0.01 µN): the tolerance 1e-15 of it is 1e-6 of the load.
turgor_add_test(fine_static_chain COMMAND turgor_app -options_file_yaml ${PROJECT_SOURCE_DIR}/config/polygon_cantilever.yaml -mode fine_static
  -control_tip_force 0,-0.01 -fine_static_times 1 -fine_static_snes_atol 1e-15 -output_dir static_chain -output_overwrite LABELS fine SETUP static_chain)
turgor_add_test(fine_static_chain_tip COMMAND ${CHECK} column static_chain/groups.csv tip_uy -1 -1.64175e-6 1e-6 LABELS fine REQUIRES static_chain)
turgor_add_test(fine_static_chain_root COMMAND ${CHECK} column static_chain/groups.csv root_fy -1 0.01 1e-6 LABELS fine REQUIRES static_chain)
# the same with PETSc's Newton (-fine_static_solver newton, the largest step capped, a line search)
turgor_add_test(fine_static_chain_newton COMMAND turgor_app -options_file_yaml ${PROJECT_SOURCE_DIR}/config/polygon_cantilever.yaml -mode fine_static
  -control_tip_force 0,-0.01 -fine_static_times 1 -fine_static_snes_atol 1e-15 -fine_static_solver newton -fine_static_snes_linesearch_type cp -output_dir static_chain_newton
  -output_overwrite LABELS fine SETUP static_chain_newton)
turgor_add_test(fine_static_chain_newton_tip COMMAND ${CHECK} column static_chain_newton/groups.csv tip_uy -1 -1.64175e-6 1e-6 LABELS fine
  REQUIRES static_chain_newton)

# The same chain under its weight, scheduled (-body_force_delay 1, -body_force_ramp_time 2): nothing at
# t = 0.5, half at t = 2, all at t = 3. The hinge at x_j carries M_j = m g sum_{i>j} (x_i - x_j), so the
# tip deflects by sum_j M_j (L - x_j) / k_r = 6.2077125e-7 µm (m = 0.5 ng, g = 2e-4 µm/µs^2); without
# the delay the ramp would be complete at t = 2.
turgor_add_test(fine_static_chain_weight COMMAND turgor_app -options_file_yaml ${PROJECT_SOURCE_DIR}/config/polygon_cantilever.yaml -mode fine_static
  -physics bars,hinges,body_force -control_tip_force 0,0 -body_force 0,-2e-4 -body_force_delay 1 -body_force_ramp_time 2 -fine_static_times 0.5,2,3
  -fine_static_snes_atol 1e-15 -output_dir static_chain_weight -output_overwrite LABELS fine SETUP static_chain_weight)
turgor_add_test(fine_static_chain_weight_tip COMMAND ${CHECK} column static_chain_weight/groups.csv tip_uy -1 -6.2077125e-7 1e-6 LABELS fine
  REQUIRES static_chain_weight)
turgor_add_test(fine_static_chain_weight_half COMMAND ${CHECK} column static_chain_weight/groups.csv tip_uy 1 -3.10385625e-7 1e-6 LABELS fine
  REQUIRES static_chain_weight)
# ... and dynamically: the ramped weight's work (the integral of f . v) balances the chain's energy
# to 1e-6 of it, the run failing otherwise
turgor_add_test(fine_chain_weight_energy COMMAND turgor_app -options_file_yaml ${PROJECT_SOURCE_DIR}/config/polygon_cantilever.yaml
  -physics bars,hinges,body_force -control_tip_force 0,0 -body_force 0,-2 -body_force_ramp_time 0.3 -fine_energy 1
  -fine_energy_tolerance 1e-6 -fine_snapshots 0 -fine_progress_interval 0 -output_dir chain_weight_energy -output_overwrite LABELS fine)
# ... also with the weight delayed: at rest before it, the chain's energies are its coordinates'
# round-off (1e-25), and the balance is judged against the round-off's energy there, not failed
turgor_add_test(fine_chain_weight_energy_delayed COMMAND turgor_app -options_file_yaml ${PROJECT_SOURCE_DIR}/config/polygon_cantilever.yaml
  -physics bars,hinges,body_force -control_tip_force 0,0 -body_force 0,-2 -body_force_delay 0.2 -body_force_ramp_time 0.3 -fine_energy 1
  -fine_energy_tolerance 1e-6 -fine_snapshots 0 -fine_progress_interval 0 -output_dir chain_weight_energy_delayed -output_overwrite LABELS fine)

# -help lists the mode's options
turgor_add_test(help_fine_static COMMAND ${HELP} fine_static -fine_static_times -fine_static_substeps -fine_static_max_cutbacks -fine_static_snapshots
  -fine_static_max_step -fine_static_solver -fine_static_psi_max_steps -fine_static_monitor -fine_clamp -controls LABELS unit)
