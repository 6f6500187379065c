"""rough.sweep on a Dask cluster survives a worker killed mid-sweep (SIGKILL, in a child process
with a time limit): the results equal the local sweep's, bit for bit."""
import subprocess
import sys
import textwrap

import pytest

SCRIPT = textwrap.dedent('''
    import os, signal, threading, time
    import numpy as np
    import fastrest
    from fastrest import rough
    from dask.distributed import Client, LocalCluster

    def main():
        steel = fastrest.Material(E=200e9, nu=0.3, Sy=1e9)
        # explicit heights (scattered) and statistical surfaces; several rounds of work per worker
        specs = [dict(material=steel, R_a=1e-4, heights=rough.gaussian_summits(150_000, 2e-8, seed=k))
                 for k in range(12)]
        specs += [dict(material=steel, R_a=1e-4, gw=dict(eta=1e10, sigma=s, A_n=1e-4))
                  for s in np.geomspace(5e-9, 5e-8, 12)]
        V = np.geomspace(0.01, 0.3, 40)
        local = rough.sweep(specs, V, 1e-2)
        with LocalCluster(n_workers=2, processes=True, threads_per_worker=1, dashboard_address=None) as cluster, \\
                Client(cluster) as client:
            client.wait_for_workers(2)
            rough.sweep(specs[:1] + specs[-1:], V, 1e-2, client=client)  # both workers compile (or load) kernels
            n_arrays = 13  # 12 explicit surfaces' heights and V1 are scattered

            def run(when):
                """The sweep with a worker SIGKILLed when ``when(number of scattered arrays)``."""
                before = set(client.who_has())
                killed = []

                def kill_a_holder():
                    t_end = time.time() + 120
                    while time.time() < t_end and not killed:
                        new = {k: ws for k, ws in client.who_has().items() if k not in before}
                        holders = {w for ws in new.values() for w in ws}
                        busy = client.processing()
                        if when(sum(k.startswith("ndarray") for k in new)):
                            for nanny in list(cluster.workers.values()):
                                if nanny.worker_address in holders and busy.get(nanny.worker_address):
                                    os.kill(nanny.process.process.pid, signal.SIGKILL)
                                    killed.append(nanny.worker_address)
                                    break
                        time.sleep(0.01)

                killer = threading.Thread(target=kill_a_holder)
                killer.start()
                t0 = time.time()
                out = rough.sweep(specs, V, 1e-2, client=client)
                elapsed = time.time() - t0
                killer.join()
                assert killed, "no worker was killed: the sweep ended first"
                client.wait_for_workers(2, timeout=120)  # the nanny restarts it
                return out, elapsed

            results = [run(lambda n: n >= 1),          # while V1 and the heights are being scattered
                       run(lambda n: n >= n_arrays)]  # once all are scattered and tasks run
        for remote, elapsed in results:
            assert remote.errors == [] and len(remote) == len(local)
            for a, b in zip(local, remote):
                for key, val in a.as_dict().items():
                    np.testing.assert_array_equal(np.asarray(b[key]), np.asarray(val), err_msg=key)
        print("OK", [round(t, 1) for _, t in results])

    if __name__ == "__main__":
        main()
''')


@pytest.mark.slow
def test_sweep_survives_a_killed_worker(tmp_path):
    """About 30-60 s on 2 cores: a LocalCluster of 2 process workers, one SIGKILLed while the
    sweep scatters its arrays, then one SIGKILLed once its tasks run."""
    pytest.importorskip("distributed")
    script = tmp_path / "sweep_kill.py"
    script.write_text(SCRIPT)
    r = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, timeout=540, cwd=tmp_path)
    assert r.returncode == 0 and "OK" in r.stdout, r.stdout[-2000:] + r.stderr[-4000:]
