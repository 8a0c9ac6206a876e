#!/usr/bin/env pvpython
"""Stand in for the ParaView GUI's Catalyst > Connect: listen for a
simulation run with paraview/catalyst_live.py, start it, and report what
arrives live.

    xvfb-run -a pvpython --disable-xdisplay-test paraview/catalyst_live_check.py \\
        PORT -- build/sph run CASE --catalyst paraview/catalyst_live.py ...

It listens on PORT (paraview.live.ConnectToCatalyst, what the GUI does),
starts the command with SPH_CATALYST_PORT=PORT, and once the connected
simulation's state lists its source "input" extracts it as the GUI's
pipeline browser does, polling it until the command ends. It prints, for every poll that had particles,
"live: N points, arrays A, B, ..." and at the end "live summary: max
points N, arrays ..., command exit status S". Exit status: the command's,
or 1 when nothing arrived.
"""
import os
import subprocess
import sys
import time
sys.dont_write_bytecode = True


def simulation_has_input(link):
    """Whether the connected simulation's state (what the GUI's pipeline
    browser lists under catalyst:) has its source "input" yet."""
    pxm = link.GetInsituProxyManager()
    return pxm is not None and pxm.GetProxy("sources", "input") is not None


def main(argv):
    if len(argv) < 3 or argv[1] != "--":
        sys.exit(__doc__)
    port = int(argv[0])
    command = argv[2:]
    from paraview import live
    link = live.ConnectToCatalyst("localhost", port)
    env = dict(os.environ, SPH_CATALYST_PORT=str(port))
    proc = subprocess.Popen(command, env=env)
    source = None
    most, arrays = 0, []
    t0 = time.time()
    while True:
        live.ProcessServerNotifications()
        if source is None and simulation_has_input(link):
            source = live.ExtractCatalystData(link, "input")
            print("live: the simulation's `input` is there after %.1f s, "
                  "extracted" % (time.time() - t0))
        if source is not None:
            source.UpdatePipeline()
            n = source.GetDataInformation().GetNumberOfPoints()
            if n > 0:
                keys = sorted(source.PointData.keys())
                print("live: %d points, arrays %s" % (n, ", ".join(keys)))
                sys.stdout.flush()
                if n > most:
                    most, arrays = n, keys
        if proc.poll() is not None:
            break
        time.sleep(0.2)
    status = proc.wait()
    print("live summary: max points %d, arrays %s, command exit status %d"
          % (most, ", ".join(arrays) or "none", status))
    return status if most > 0 else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
