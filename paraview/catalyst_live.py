"""Live view of a running sph simulation in the ParaView GUI: a ParaView
Catalyst pipeline script (legacy "Catalyst 1": RequestDataDescription and
DoCoProcessing) for `sph run --catalyst`.

1. In the ParaView GUI: Catalyst > Connect (port 22222), and Catalyst >
   Pause Simulation first if the run must wait at its first step.
2. Run:
       build/sph run cases/dam_break.case --catalyst paraview/catalyst_live.py \\
           --catalyst_every 10
3. The run appears in the Pipeline Browser under catalyst: as "input";
   click the icon next to it to extract it, then Show it and colour it
   (by pressure: its legend gives the unit, "pressure (N/m)" in 2D);
   paraview/render.py's look is a File > Load State of a paraview/*.pvsm
   away for files, not for the live source. Catalyst > Pause Simulation
   stops sph at its next hand-over, Continue lets it go on.

Each time sph hands over the particles (at the start, every catalyst_every
steps and at the end) Catalyst tries to connect to the GUI: with no GUI
listening it says so once and the run goes on, untouched. No X display is
needed (nothing is rendered in the simulation).

Settings, from the environment of `sph run`:
    SPH_CATALYST_HOST   the GUI's machine (default localhost)
    SPH_CATALYST_PORT   its Catalyst port (default 22222, ParaView's default)
"""
import os
import sys
sys.dont_write_bytecode = True   # keep the source tree clean

from paraview import coprocessing  # noqa: E402

HOST = os.environ.get("SPH_CATALYST_HOST", "localhost")
try:
    PORT = int(os.environ.get("SPH_CATALYST_PORT", "22222"))
except ValueError:
    raise SystemExit("SPH_CATALYST_PORT must be a port number, 1 to 65535")
if not 0 < PORT < 65536:
    raise SystemExit("SPH_CATALYST_PORT must be a port number, 1 to 65535")


class _CoProcessor(coprocessing.CoProcessor):
    """The particles as the source "input"; nothing written, nothing rendered."""

    def CreatePipeline(self, datadescription):
        self.CreateProducer(datadescription, "input")


def _make():
    c = _CoProcessor()
    c.SetUpdateFrequencies({"input": [1]})   # every hand-over sph makes
    c.EnableLiveVisualization(True, 1)
    return c


_coprocessor = _make()


def RequestDataDescription(datadescription):
    _coprocessor.LoadRequestedData(datadescription)


def DoCoProcessing(datadescription):
    _coprocessor.UpdateProducers(datadescription)
    _coprocessor.DoLiveVisualization(datadescription, HOST, PORT)


def Finalize():
    _coprocessor.Finalize()
