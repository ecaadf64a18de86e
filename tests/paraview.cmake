# ParaView as the client: open the fine run's particles.xmf and the FE^2 run's coarse.xmf with the
# reader ParaView picks for .xmf (its Xdmf3 reader) and with the legacy XDMF reader, go to the last
# time step, fetch the data and check cells, arrays (components, integer types) and the tip
# displacement against summary.json (check_paraview.py; the FE^2 one through Warp By Vector).
# No window is opened (nothing is rendered), so no X server is needed. Added only where pvpython is
# found (Debian: apt-get install paraview python3-paraview python3-numpy); elsewhere nothing is added.
# Each check starts pvpython (2 s): the default tier reads each kind of output once with the default
# reader and the fine run's with the legacy reader too; the other legacy reads are long.
find_program(TURGOR_PVPYTHON pvpython)
if(NOT TURGOR_PVPYTHON)
  message(STATUS "pvpython not found: the ParaView client tests (label paraview) are not added")
  return()
endif()
message(STATUS "pvpython: ${TURGOR_PVPYTHON}: adding the ParaView client tests (label paraview)")
set(PVCHECK ${TURGOR_PVPYTHON} --force-offscreen-rendering ${CMAKE_CURRENT_SOURCE_DIR}/check_paraview.py)
turgor_add_test(paraview_fine COMMAND ${PVCHECK} fine small_rk LABELS paraview fine REQUIRES small_rk TIMEOUT 120)
turgor_add_test(paraview_fine_legacy COMMAND ${PVCHECK} fine small_rk --reader XDMFReader LABELS paraview fine REQUIRES small_rk TIMEOUT 120)
turgor_add_test(paraview_fe2 COMMAND ${PVCHECK} fe2 fe2_mpi2 LABELS paraview fe2 REQUIRES fe2_mpi2 TIMEOUT 120)
turgor_add_test(paraview_fe2_legacy COMMAND ${PVCHECK} fe2 fe2_mpi2 --reader XDMFReader LABELS paraview fe2 long REQUIRES fe2_mpi2 TIMEOUT 120)
# -mode eigen's mode shapes (modes.xmf): one step per mode, each a Warp By Vector away
turgor_add_test(paraview_modes COMMAND ${PVCHECK} modes eigen_bar LABELS paraview eigen REQUIRES eigen_bar TIMEOUT 120)
turgor_add_test(paraview_modes_legacy COMMAND ${PVCHECK} modes eigen_bar --reader XDMFReader LABELS paraview eigen long REQUIRES eigen_bar TIMEOUT 120)
