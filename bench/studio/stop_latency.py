#!/usr/bin/env python3
"""How long the studio's Stop takes when it lands at a given time after Render.

    python3 bench/studio/stop_latency.py BUILD/insitu SCENE [DELAY_S ...]

Starts `insitu studio SCENE --port 0`, and for each delay posts a render, waits that long, posts
a stop and times its reply (the reply comes once the worker has ended). Prints one line per delay:
the delay, the state the stop left, whether the light was published (the load had finished), and
the stop's time. A delay past the load lands in the integrator's preparation or the sample loop.
"""
import json
import re
import subprocess
import sys
import time
import urllib.request


def main() -> None:
    insitu, scene = sys.argv[1], sys.argv[2]
    delays = [float(d) for d in sys.argv[3:]] or [0.5, 1, 2, 4]
    studio = subprocess.Popen([insitu, "studio", scene, "--port", "0"], stdout=subprocess.PIPE, text=True)
    try:
        url = None
        for line in studio.stdout:
            m = re.search(r"(http://127\.0\.0\.1:\d+)/\?token=([0-9a-f]+)", line)
            if m:
                url, token = m.group(1), m.group(2)
                break
        headers = {"Authorization": "token " + token, "Origin": url, "Content-Type": "application/json"}

        def call(path: str, body: dict | None = None) -> dict:
            data = None if body is None else json.dumps(body).encode()
            req = urllib.request.Request(url + path, data=data, headers=headers, method="GET" if data is None else "POST")
            with urllib.request.urlopen(req, timeout=600) as r:
                return json.loads(r.read())

        for delay in delays:
            call("/api/render", {"spp": 1 << 20})
            time.sleep(delay)
            t0 = time.monotonic()
            s = call("/api/render/stop", {})
            print(f"stop at {delay:5.2f} s: {s['state']:8s} light {str(s['light']):5s} took {time.monotonic() - t0:6.3f} s")
    finally:
        studio.terminate()
        studio.wait()


if __name__ == "__main__":
    main()
