"""The rig of an SSP run in libcosim, in a subprocess of its own (libcosim
and fmpy in one process have crashed): (x1, x2, driveForce) of the rig FMU
after each of n steps.  Shared by the SSP and export tests."""
import json
import subprocess
import sys

SCRIPT = r"""
import json, sys
from libcosimpy.CosimExecution import CosimExecution
from libcosimpy.CosimObserver import CosimObserver
from libcosimpy.CosimLogging import log_output_level, CosimLogLevel
log_output_level(CosimLogLevel.ERROR)
ex = CosimExecution.from_ssp_file(sys.argv[1])
rig = {i.name.decode(): i.index for i in ex.slave_infos()}["rig"]
vr = {v.name.decode(): v.reference for v in ex.slave_variables(rig)}
obs = CosimObserver.create_last_value(); ex.add_observer(observer=obs)
rows = []
for k in range(int(sys.argv[2])):
    assert ex.step()
    rows.append(obs.last_real_values(rig, [vr["x1"], vr["x2"], vr["driveForce"]]))
print(json.dumps(rows))
"""


def run_rig_ssp(ssp, n: int) -> list:
    """[[x1, x2, driveForce], ...] over n steps of the SSP in libcosim."""
    q = subprocess.run([sys.executable, "-c", SCRIPT, str(ssp), str(n)], capture_output=True, text=True,
                       timeout=600)
    assert q.returncode == 0, q.stderr[-2000:]
    return json.loads(q.stdout.strip().splitlines()[-1])  # libcosim logs to stdout
