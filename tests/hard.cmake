# The hard-case suite (label hard): legal but demanding scenes from config/hard/, each with its
# expected outcome (written in the scene's header too): it completes and its answer is checked
# against a second method, an analytic value or a tighter run -- or it fails cleanly: exit status 1,
# the reason named, summary.json "failed" (tests/expect_error.py). Cases marked np2 run on two
# MPI ranks as well. The long tier holds the slow runs (over 5 s) and the second runs whose check
# repeats another case's: another integrator, more ranks or a tighter tolerance for the same scene.
set(HARD ${PROJECT_SOURCE_DIR}/config/hard)
set(VERLET -ts_type basicsymplectic -fine_dt_safety 0.5)
# a run of scene NAME (extra options after it) into hard/OUT, a fixture for the checks
function(turgor_hard_run out scene)
  turgor_add_test(hard_${out} COMMAND turgor_app -options_file_yaml ${HARD}/${scene}.yaml -output_dir hard/${out} -output_overwrite ${ARGN}
    LABELS hard SETUP hard_${out} TIMEOUT 300)
endfunction()
function(turgor_hard_run_np2 out scene)
  turgor_add_test(hard_${out} COMMAND ${MPIEXEC_ROOT} -n 2 $<TARGET_FILE:turgor_app> -options_file_yaml ${HARD}/${scene}.yaml -output_dir hard/${out}
    -output_overwrite ${ARGN} LABELS hard mpi SETUP hard_${out} TIMEOUT 300)
endfunction()
# a check on the fixtures it names
function(turgor_hard_check name requires)
  turgor_add_test(hard_${name} COMMAND ${ARGN} LABELS hard REQUIRES "${requires}")
endfunction()
# a scene that must fail cleanly with a message matching REGEX
function(turgor_hard_fails name scene regex)
  turgor_add_test(hard_${name} COMMAND ${BAD} "${regex}" $<TARGET_FILE:turgor_app> -options_file_yaml ${HARD}/${scene}.yaml -output_dir hard/${name}
    -output_overwrite ${ARGN} LABELS hard TIMEOUT 300)
endfunction()
function(turgor_hard_fails_np2 name scene regex)
  turgor_add_test(hard_${name} COMMAND ${BAD} "${regex}" ${MPIEXEC_ROOT} -n 2 $<TARGET_FILE:turgor_app> -options_file_yaml ${HARD}/${scene}.yaml -output_dir
    hard/${name} -output_overwrite ${ARGN} LABELS hard mpi TIMEOUT 300)
endfunction()
set(HCHECK ${CMAKE_CURRENT_SOURCE_DIR}/compare_runs.py)

# --- fine
# 1000x stiffer walls: DOPRI and Verlet agree; so do 1 and 2 ranks (np2)
turgor_hard_run(fine_stiff_walls fine_stiff_walls)
turgor_hard_run(fine_stiff_walls_verlet fine_stiff_walls ${VERLET})
turgor_hard_run_np2(fine_stiff_walls_np2 fine_stiff_walls)
turgor_hard_check(fine_stiff_walls_agree "hard_fine_stiff_walls;hard_fine_stiff_walls_verlet" ${HCHECK} tiprel hard/fine_stiff_walls_verlet hard/fine_stiff_walls 1e-5)
turgor_hard_check(fine_stiff_walls_ranks "hard_fine_stiff_walls;hard_fine_stiff_walls_np2" ${HCHECK} tip hard/fine_stiff_walls_np2 hard/fine_stiff_walls 1e-10)
# ... and the low-storage pair (TS lsrk, DSP controller) against DOPRI at the scene's tolerance
turgor_hard_run(fine_stiff_walls_lsrk fine_stiff_walls -ts_type lsrk)
turgor_hard_check(fine_stiff_walls_lsrk_agree "hard_fine_stiff_walls;hard_fine_stiff_walls_lsrk" ${HCHECK} tiprel hard/fine_stiff_walls_lsrk hard/fine_stiff_walls
  1e-5)
# TS verlet with the dashpots and the SPH viscosity at the velocity predicted to the step's end
# (-fine_predict_velocity, at its halved limit: the same step as Verlet at 0.5): 1.5e-8 from DOPRI
# at 1e-6 (the drift's velocity at that step: 8.7e-6, first order)
turgor_hard_run(fine_stiff_walls_predicted fine_stiff_walls -ts_type verlet -fine_predict_velocity -fine_dt_safety 1)
turgor_hard_check(fine_stiff_walls_predicted_agree "hard_fine_stiff_walls;hard_fine_stiff_walls_predicted" ${HCHECK} tiprel hard/fine_stiff_walls_predicted
  hard/fine_stiff_walls 1e-7)
turgor_long(hard_fine_stiff_walls hard_fine_stiff_walls_verlet hard_fine_stiff_walls_agree hard_fine_stiff_walls_np2 hard_fine_stiff_walls_ranks
  hard_fine_stiff_walls_predicted hard_fine_stiff_walls_predicted_agree hard_fine_stiff_walls_lsrk hard_fine_stiff_walls_lsrk_agree)
# 500x load: DOPRI and Verlet agree
turgor_hard_run(fine_large_load fine_large_load)
turgor_hard_run(fine_large_load_verlet fine_large_load ${VERLET})
turgor_hard_check(fine_large_load_agree "hard_fine_large_load;hard_fine_large_load_verlet" ${HCHECK} tiprel hard/fine_large_load_verlet hard/fine_large_load 1e-2)
# tolerances 1e-1 and 1e-9; Verlet at 0.1x and 1x its limit; 2x its limit fails cleanly
turgor_hard_run(fine_loose_tolerance fine_loose_tolerance)
turgor_hard_run(fine_tight_tolerance fine_tight_tolerance)
turgor_hard_run(fine_verlet_tenth_limit fine_verlet_tenth_limit)
turgor_hard_run(fine_verlet_at_limit fine_verlet_at_limit)
turgor_hard_check(fine_loose_tolerance_bound "hard_fine_loose_tolerance;hard_fine_tight_tolerance" ${HCHECK} tiprel hard/fine_loose_tolerance hard/fine_tight_tolerance 1e-2)
turgor_hard_check(fine_tight_tolerance_agrees "hard_fine_tight_tolerance;hard_fine_verlet_tenth_limit" ${HCHECK} tiprel hard/fine_verlet_tenth_limit hard/fine_tight_tolerance
  5e-5)
turgor_hard_check(fine_verlet_at_limit_agrees "hard_fine_tight_tolerance;hard_fine_verlet_at_limit" ${HCHECK} tiprel hard/fine_verlet_at_limit hard/fine_tight_tolerance
  5e-4)
turgor_long(hard_fine_verlet_tenth_limit hard_fine_tight_tolerance_agrees)
turgor_hard_fails(fine_verlet_twice_limit fine_verlet_at_limit "Non-finite acceleration of particle [0-9]+ at t = .*the fixed step is above the stability limit"
  -ts_dt 0.0027)
# a bar 100 times shorter with plastic hinges: below the hinges' limit the plastic dissipation
# converges (dt 3e-5 and 2e-5 agree); at 1.8 times the limit the step is warned about by its term
turgor_hard_run(fine_short_bar_hinges fine_short_bar_hinges -tissue_node_file ${HARD}/short_bar.nodes)
turgor_hard_run(fine_short_bar_hinges_finer fine_short_bar_hinges -tissue_node_file ${HARD}/short_bar.nodes -ts_dt 2e-5)
turgor_hard_check(fine_short_bar_hinges_converged "hard_fine_short_bar_hinges;hard_fine_short_bar_hinges_finer" ${HCHECK} samekey hard/fine_short_bar_hinges
  hard/fine_short_bar_hinges_finer hinge_plastic_dissipation 1e-5)
turgor_hard_check(fine_short_bar_hinges_balance hard_fine_short_bar_hinges ${HCHECK} between hard/fine_short_bar_hinges energy_residual_max 0 1e-5)
turgor_add_test(hard_fine_short_bar_hinges_above COMMAND turgor_app -options_file_yaml ${HARD}/fine_short_bar_hinges.yaml -tissue_node_file
  ${HARD}/short_bar.nodes -ts_dt 5e-5 -output_dir hard/fine_short_bar_hinges_above -output_overwrite LABELS hard PASS_REGEX
  "WARNING: the fixed step 5e-05 µs exceeds the smallest stability limit 2.788e-05 µs \\(hinges: .*\\) 1.79 times.*plastic hinges")
# a long run: a damped oscillation about the static deflection
turgor_hard_run(fine_long_time fine_long_time)
turgor_hard_check(fine_long_time_settles hard_fine_long_time ${HCHECK} settling hard/fine_long_time 3e-2)
turgor_long(hard_fine_long_time hard_fine_long_time_settles)
# loss of turgor and flaccid cells: DOPRI's answer does not depend on its tolerance
foreach(case loss_of_turgor flaccid)
  turgor_hard_run(fine_${case} fine_${case})
  turgor_hard_run(fine_${case}_tight fine_${case} -ts_rtol 1e-6 -ts_atol 1e-6)
  turgor_hard_check(fine_${case}_converged "hard_fine_${case};hard_fine_${case}_tight" ${HCHECK} tiprel hard/fine_${case} hard/fine_${case}_tight 2e-4)
endforeach()
# walls without springs: the tissue falls freely
turgor_hard_run(fine_zero_stiffness_walls fine_zero_stiffness_walls)
turgor_hard_check(fine_zero_stiffness_walls_fall hard_fine_zero_stiffness_walls ${HCHECK} freefall hard/fine_zero_stiffness_walls 0.2 1e-4)

# --- rve
# shear to 500%: a wall is crossed near F12 = 0.9 (named, failed summary), on 1 and 2 ranks
turgor_hard_fails(rve_shear_500 rve_shear_500 "evaluation failed: .*(F = \\[1\\. 1\\.3; 0\\. 1\\.\\])")
turgor_hard_fails_np2(rve_shear_500_np2 rve_shear_500 "evaluation failed: .*(F = \\[1\\. 1\\.3; 0\\. 1\\.\\])")
turgor_long(hard_rve_shear_500_np2)
# compression to 1%: relaxes down to 3%, fails cleanly at 1%
turgor_hard_fails(rve_compression_99 rve_compression_99 "t = 68\\. µs: evaluation failed: the relaxed RVE has fluid particles outside their cell")
# the same with Anderson-accelerated warm solves (-rve_anderson): another equilibrium at 68 µs (an
# admissible one), then Psi-tc stops converging at 98 µs (97 % compression): a clean failure, named
turgor_hard_fails(rve_compression_99_anderson rve_compression_99 "t = 98\\. µs: evaluation failed: Psi-tc did not converge" -rve_anderson)
# 1000x stiffer walls: the stress and the tangent of the stretched walls, k_w eps / 2 and k_w / 2
turgor_hard_run(rve_stiff_walls rve_stiff_walls)
turgor_hard_check(rve_stiff_walls_stress hard_rve_stiff_walls ${HCHECK} column hard/rve_stiff_walls/rve.csv s11 -1 1e5 1e-3 0)
turgor_hard_check(rve_stiff_walls_tangent hard_rve_stiff_walls ${HCHECK} column hard/rve_stiff_walls/rve.csv De11_11 -1 2e6 1e-3)

# --- fe2
# 100x load: the RVEs' walls are crossed; the run fails cleanly, naming where and why (np2 too)
turgor_hard_fails(fe2_large_load fe2_large_load "material points failed at t = .*(fluid particles outside their cell|Psi-tc did not converge)")
turgor_hard_fails_np2(fe2_large_load_np2 fe2_large_load "material points failed at t = .*(fluid particles outside their cell|Psi-tc did not converge)")
turgor_long(hard_fe2_large_load_np2)
# tolerances 1e-1 and 1e-9
turgor_hard_run(fe2_loose_tolerance fe2_loose_tolerance)
turgor_hard_run(fe2_tight_tolerance fe2_tight_tolerance)
turgor_hard_check(fe2_loose_tolerance_bound "hard_fe2_loose_tolerance;hard_fe2_tight_tolerance" ${HCHECK} tiprel hard/fe2_loose_tolerance hard/fe2_tight_tolerance 5e-3)
turgor_long(hard_fe2_loose_tolerance hard_fe2_tight_tolerance hard_fe2_loose_tolerance_bound)
# 1000x stiffer walls: Radau IIA and DOPRI agree; 1 and 2 ranks agree
turgor_hard_run(fe2_stiff_walls fe2_stiff_walls)
turgor_hard_run(fe2_stiff_walls_rk fe2_stiff_walls -ts_type rk)
turgor_hard_run_np2(fe2_stiff_walls_np2 fe2_stiff_walls)
turgor_hard_check(fe2_stiff_walls_agree "hard_fe2_stiff_walls;hard_fe2_stiff_walls_rk" ${HCHECK} tiprel hard/fe2_stiff_walls_rk hard/fe2_stiff_walls 1e-3)
turgor_hard_check(fe2_stiff_walls_ranks "hard_fe2_stiff_walls;hard_fe2_stiff_walls_np2" ${HCHECK} tiprel hard/fe2_stiff_walls_np2 hard/fe2_stiff_walls 1e-6)
# a crushed neo-Hookean tissue: steps that invert an element are rejected; the answer converges
turgor_hard_run(fe2_neo_hookean_crush fe2_neo_hookean_crush)
turgor_hard_run(fe2_neo_hookean_crush_tight fe2_neo_hookean_crush -ts_rtol 1e-7 -ts_atol 1e-7)
turgor_hard_check(fe2_neo_hookean_crush_rejects hard_fe2_neo_hookean_crush ${HCHECK} positive hard/fe2_neo_hookean_crush rejected_steps)
turgor_hard_check(fe2_neo_hookean_crush_converged "hard_fe2_neo_hookean_crush;hard_fe2_neo_hookean_crush_tight" ${HCHECK} tiprel hard/fe2_neo_hookean_crush
  hard/fe2_neo_hookean_crush_tight 1e-3)
turgor_long(hard_fe2_neo_hookean_crush_tight hard_fe2_neo_hookean_crush_converged)
# inverted and collapsed elements in the mesh: refused before any work
turgor_hard_fails(fe2_folded_element fe2_loose_tolerance "Coarse mesh: element [0-9]+ with vertices .* is degenerate or folded"
  -coarse_dm_plex_filename ${CMAKE_CURRENT_SOURCE_DIR}/data/folded_quad.msh)
turgor_hard_fails(fe2_collapsed_element fe2_loose_tolerance "Coarse mesh: element [0-9]+ with vertices .* is degenerate or folded: det J = 0"
  -coarse_dm_plex_filename ${CMAKE_CURRENT_SOURCE_DIR}/data/collapsed_quad.msh)
# cells turned inside out by suction fail the run, named (1 and 2 ranks: the owner of the cell finds it)
turgor_hard_fails(fine_suction_inverts fine_suction_inverts "Cell [0-9]+ turned inside out at t = [0-9.e-]+ µs: its area is -[0-9.e+]+ µm²")
turgor_hard_fails_np2(fine_suction_inverts_np2 fine_suction_inverts "Cell [0-9]+ turned inside out at t = [0-9.e-]+ µs")
# a velocity control faster than a quarter of the contact reach per fixed step is refused, named
# (the lid at 1e6 µm/µs would move 640 µm a step straight through the tissue); 1 and 2 ranks
set(CONTROL_TOO_FAST -options_file_yaml ${PROJECT_SOURCE_DIR}/config/polygon_compression.yaml -tissue_voronoi_cells 16 -tissue_box 0,0,100,100
  -ts_max_time 2 -fine_snapshots 0 -fine_progress_interval 0 -control_lid_velocity 0,-1e6 -control_lid_delay 0.5)
turgor_add_test(hard_fine_control_too_fast COMMAND ${BAD} "Option -control_lid_velocity: 1e\\+06 µm/µs moves its nodes [0-9.]+ µm in a step of"
  $<TARGET_FILE:turgor_app> ${CONTROL_TOO_FAST} -output_dir hard/fine_control_too_fast -output_overwrite LABELS hard badinput TIMEOUT 120)
turgor_add_test(hard_fine_control_too_fast_np2 COMMAND ${BAD} "Option -control_lid_velocity: 1e\\+06 µm/µs moves its nodes" ${MPIEXEC_ROOT} -n 2
  $<TARGET_FILE:turgor_app> ${CONTROL_TOO_FAST} -output_dir hard/fine_control_too_fast_np2 -output_overwrite LABELS hard badinput mpi TIMEOUT 120)
# a stiff elastic turgor (K = 1e7 N/m): the pressure term's own stability line sets the step (the
# rank-one -dp/dA g g^T part exactly, the rest by Gershgorin), so the run stays stable
turgor_add_test(hard_fine_stiff_turgor COMMAND turgor_app -options_file_yaml ${PROJECT_SOURCE_DIR}/config/polygon_compression.yaml
  -tissue_voronoi_cells 16 -tissue_box 0,0,100,100 -ts_max_time 0.5 -contact_damping 0 -pressure_law elastic -pressure_bulk_modulus 1e7
  -fine_snapshots 0 -fine_progress_interval 0 -output_dir hard/fine_stiff_turgor -output_overwrite LABELS hard SETUP hard_fine_stiff_turgor)
turgor_hard_check(fine_stiff_turgor_limit hard_fine_stiff_turgor ${HCHECK} between hard/fine_stiff_turgor dt_stable 2.9e-4 3.1e-4)
turgor_hard_check(fine_stiff_turgor_finite hard_fine_stiff_turgor ${HCHECK} keys hard/fine_stiff_turgor tip_displacement_final)
# a stiff elastic turgor (K = 1e6 N/m) at the default step with the energy balance on: Verlet's
# residual (11 % within 0.005 µs) is above -fine_energy_tolerance's 1 %, and the run fails naming it
turgor_add_test(hard_fine_energy_exceeded COMMAND ${BAD} "Energy balance: residual -?[0-9.e+-]+ at t = [0-9.e-]+ µs, -?[0-9.e-]+ of the work .* above -fine_energy_tolerance 0.01"
  $<TARGET_FILE:turgor_app> -options_file_yaml ${PROJECT_SOURCE_DIR}/config/polygon_compression.yaml -tissue_voronoi_cells 16 -tissue_box 0,0,100,100
  -ts_max_time 0.5 -contact_damping 0 -pressure_law elastic -pressure_bulk_modulus 1e6 -fine_snapshots 0 -fine_progress_interval 0 -fine_energy
  -output_dir hard/fine_energy_exceeded -output_overwrite LABELS hard badinput TIMEOUT 120)
# frictionless, undamped contact of a tissue inflating into a box conserves energy to Verlet's
# O(dt^2): halving the step cuts the largest residual at least 3x (measured 4.0x)
foreach(s 0.25 0.125)
  turgor_hard_run(fine_contact_conservative_${s} fine_contact_conservative -fine_dt_safety ${s})
endforeach()
turgor_hard_check(fine_contact_conservative_order "hard_fine_contact_conservative_0.25;hard_fine_contact_conservative_0.125" ${HCHECK} notmore
  hard/fine_contact_conservative_0.125 hard/fine_contact_conservative_0.25 energy_residual_max -0.67)
# the same tissue with friction, the contact dashpot and viscosity (the compression scene's physics):
# the dashpot's work counted as dissipation, the balance closes to well within 1 % at a quarter of the limit
turgor_add_test(hard_fine_box_dissipation COMMAND turgor_app -options_file_yaml ${PROJECT_SOURCE_DIR}/config/polygon_compression.yaml -tissue_voronoi_cells 16
  -tissue_box 0,0,100,100 -ts_max_time 2 -fine_snapshots 0 -fine_progress_interval 0 -fine_energy -fine_dt_safety 0.125 -output_dir hard/fine_box_dissipation
  -output_overwrite LABELS hard SETUP hard_fine_box_dissipation)
turgor_hard_check(fine_box_dissipation_balance hard_fine_box_dissipation ${HCHECK} between hard/fine_box_dissipation energy_residual_max 0 4e-3)
