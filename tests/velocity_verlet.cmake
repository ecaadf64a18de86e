# The TS type verlet (src/ts/velocity_verlet.cpp) when a step goes wrong: a non-finite end fails the
# solve without any domain check, a step the user's domain check rejects is undone to round-off.
# (Its order and energy behaviour: test_spring_chain.)
turgor_test_program(test_velocity_verlet)
turgor_add_test(test_velocity_verlet COMMAND test_velocity_verlet -malloc_debug LABELS ts unit)
