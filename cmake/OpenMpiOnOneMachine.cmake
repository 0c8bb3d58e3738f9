# Open MPI in a container, as root, on one machine, for the scripts that run mpirun
# (tests/app/MpiGeneration.cmake, tests/paraview/RunPvbatch.cmake): no ssh launcher, shared
# memory and loopback only, no single-copy mechanism that needs ptrace, more ranks than cores
# allowed. include() it from a `cmake -P` script before its first mpirun.
set(ENV{OMPI_MCA_plm_rsh_agent} "")
set(ENV{OMPI_MCA_btl} "self,vader")
set(ENV{OMPI_MCA_btl_vader_single_copy_mechanism} "none")
set(ENV{OMPI_MCA_oob_tcp_if_include} "lo")
set(ENV{OMPI_MCA_rmaps_base_oversubscribe} "1")
set(ENV{OMPI_ALLOW_RUN_AS_ROOT} "1")
set(ENV{OMPI_ALLOW_RUN_AS_ROOT_CONFIRM} "1")
