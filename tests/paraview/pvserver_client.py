"""paraview.pvserver.two_ranks: `mpirun -np 2 pvserver` on a free port of this machine, and
PvserverClient.py in pvpython connecting to it (the issue's "pvbatch (and pvserver)"). Passes when
the client draws the cloud and exits 0 and the server exits once the client has gone; every
process has a timeout, so a hang fails the test.

Usage: python3 pvserver_client.py PVSERVER PVPYTHON MPIRUN WORK_DIR"""
import os
import socket
import subprocess
import sys

pvserver, pvpython, mpirun, work = sys.argv[1:5]
os.makedirs(work, exist_ok=True)
here = os.path.dirname(os.path.abspath(__file__))
env = dict(os.environ)
# Open MPI in a container, as root, on one machine (cmake/OpenMpiOnOneMachine.cmake).
env.update({"OMPI_MCA_plm_rsh_agent": "", "OMPI_MCA_btl": "self,vader",
            "OMPI_MCA_btl_vader_single_copy_mechanism": "none", "OMPI_MCA_oob_tcp_if_include": "lo",
            "OMPI_MCA_rmaps_base_oversubscribe": "1", "OMPI_ALLOW_RUN_AS_ROOT": "1",
            "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1"})

with socket.socket() as probe:
    probe.bind(("localhost", 0))
    port = probe.getsockname()[1]

server = subprocess.Popen([mpirun, "-np", "2", pvserver, "--server-port=%d" % port,
                           "--force-offscreen-rendering"], env=env, cwd=work,
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
try:
    for line in server.stdout:  # until the server listens
        sys.stdout.write("server: " + line)
        if "Waiting for client" in line:
            break
    else:
        sys.exit("pvserver ended before it listened (status %s)" % server.wait())
    client = subprocess.run([pvpython, "--force-offscreen-rendering",
                             os.path.join(here, "PvserverClient.py"), str(port), "client.png"],
                            env=env, cwd=work, capture_output=True, text=True, timeout=240)
    sys.stdout.write(client.stdout + client.stderr)
    if client.returncode != 0:
        sys.exit("the client exited %d" % client.returncode)
    rest, _ = server.communicate(timeout=60)
    sys.stdout.write("server: " + rest.replace("\n", "\nserver: "))
    if server.returncode != 0:
        sys.exit("pvserver exited %d after the client left" % server.returncode)
finally:
    if server.poll() is None:
        server.kill()
