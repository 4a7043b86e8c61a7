"""The Python module (python/insitu_module.cpp) against the CLI: the demo's layers as numpy arrays
are the CLI's EXR channels bit for bit; progress and cancellation; errors as insitu.Error with the
CLI's message; meshes and control points from numpy; the README's example runs.

Run by ctest with PYTHONPATH at the built module and INSITU_BINARY, INSITU_SOURCE_DIR set."""
import os
import subprocess
import sys
import tempfile
import threading
import unittest

import numpy as np
import OpenImageIO as oiio

import insitu

SOURCE = os.environ["INSITU_SOURCE_DIR"]
BINARY = os.environ["INSITU_BINARY"]
DEMO = os.path.join(SOURCE, "scenes", "demo", "scene.json")


def exr_channels(path):
    """name -> float32 array (height, width) of every channel of an EXR."""
    image = oiio.ImageInput.open(path)
    spec = image.spec()
    pixels = image.read_image(0, 0, 0, spec.nchannels, "float")
    image.close()
    return {name: pixels[:, :, c] for c, name in enumerate(spec.channelnames)}


def exr_name(layer, channel):
    return channel if layer == "composite" else f"{layer}.{channel}"


CHANNELS = {1: {"depth": "Z"}, 3: {"normal": "XYZ"}}


def channel_names(layer, count):
    if count == 1:
        return ["Z" if layer == "depth" else "Y"]
    return list(CHANNELS[3].get(layer, "RGB")) if count == 3 else ["R", "G", "B", "A"]


class DemoAgainstTheCli(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        out = os.path.join(cls.tmp.name, "demo.png")
        subprocess.run([BINARY, "render", DEMO, "-o", out, "--spp", "2"], check=True, capture_output=True)
        cls.exr = exr_channels(os.path.join(cls.tmp.name, "demo.layers.exr"))
        scene = insitu.Scene(DEMO)
        scene.set("render.spp", 2)
        cls.progress = []
        cls.result = scene.render(progress=lambda p: cls.progress.append(p))

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_layers_are_the_exr_bit_for_bit(self):
        compared = 0
        for name, array in self.result.layers.items():
            self.assertEqual(array.dtype, np.float32)
            self.assertEqual(array.shape[:2], (self.result.height, self.result.width))
            if name == "display":
                continue
            for c, channel in enumerate(channel_names(name, array.shape[2])):
                expected = self.exr[exr_name(name, channel)]
                self.assertTrue(np.array_equal(array[:, :, c], expected), f"{name}.{channel}")
                compared += 1
        self.assertEqual(compared, len(self.exr))

    def test_progress_and_report(self):
        self.assertEqual(self.result.spp, 2)
        self.assertFalse(self.result.cancelled)
        passes = [p for p in self.progress if p["noise"] >= 0]
        self.assertEqual([p["spp_done"] for p in passes], [1, 2])
        self.assertEqual(self.progress[-1]["fraction"], 1.0)
        self.assertEqual(self.result.report["render"]["spp"], 2)


class Module(unittest.TestCase):
    def test_errors_carry_the_clis_message_and_code(self):
        with self.assertRaises(insitu.Error) as e:
            insitu.Scene("/nonexistent/scene.json")
        self.assertEqual(str(e.exception), "/nonexistent/scene.json: file not found")
        self.assertEqual(e.exception.code, insitu.INPUT_ERROR)
        scene = insitu.Scene(DEMO)
        with self.assertRaises(insitu.Error) as e:
            scene.set("render.spp", -1)
        self.assertIn("$.render.spp", str(e.exception))
        with self.assertRaises(insitu.Error) as e:
            scene.set("render.spp", 1)
            scene.render().layer("colour")
        self.assertEqual(e.exception.code, insitu.ARGUMENT_ERROR)

    def test_cancel_from_the_callback_and_a_raising_callback(self):
        scene = insitu.Scene(DEMO)
        scene.set("render.spp", 64)
        result = scene.render(progress=lambda p: p["fraction"] > 0.2)
        self.assertTrue(result.cancelled)
        self.assertLess(result.spp, 64)

        def boom(p):
            raise RuntimeError("from the callback")
        with self.assertRaisesRegex(RuntimeError, "from the callback"):
            scene.render(progress=boom)

    def test_resumable_render_is_bit_identical(self):
        scene = insitu.Scene(DEMO)
        scene.set("render.spp", 4)
        whole = scene.render()
        with tempfile.TemporaryDirectory() as tmp:
            checkpoint = os.path.join(tmp, "demo.checkpoint")
            part = scene.render(progress=lambda p: p["fraction"] > 0.3, checkpoint=checkpoint)
            self.assertTrue(part.cancelled)
            self.assertTrue(os.path.exists(checkpoint))
            rest = scene.render(checkpoint=checkpoint)
            self.assertFalse(os.path.exists(checkpoint))
        for name in ("composite", "objects", "with", "without"):
            self.assertTrue(np.array_equal(rest.layers[name], whole.layers[name]), name)

    def test_cancel_from_another_thread(self):
        scene = insitu.Scene(DEMO)
        scene.set("render.spp", 4096)
        started = threading.Event()

        def cancel():
            started.wait()
            scene.cancel()
        t = threading.Thread(target=cancel)
        t.start()
        result = scene.render(progress=lambda p: started.set() and False)
        t.join()
        self.assertTrue(result.cancelled)

    def test_a_scene_rendering_in_another_thread_refuses_other_calls(self):
        """render() releases the GIL; a call on the same scene from another thread meanwhile was a
        use-after-free (issue 46). It is refused with insitu.Error, and the scene is usable again
        once the render has ended."""
        scene = insitu.Scene(DEMO)
        scene.set("render.spp", 4096)
        started, checked = threading.Event(), threading.Event()
        results = []
        t = threading.Thread(target=lambda: results.append(scene.render(progress=lambda p: started.set() and False)))
        t.start()
        self.assertTrue(started.wait(300))
        try:
            for call in (lambda: scene.set("render.spp", 1), lambda: scene.render(), lambda: scene.camera,
                         lambda: scene.warnings, lambda: scene.add_obj(os.path.join(SOURCE, "scenes", "demo", "ball.obj"))):
                with self.assertRaises(insitu.Error) as caught:
                    call()
                self.assertEqual(caught.exception.code, insitu.ARGUMENT_ERROR)
                self.assertIn("under way in another thread", str(caught.exception))
        finally:
            scene.cancel()
            t.join()
        self.assertTrue(results[0].cancelled)
        scene.set("render.spp", 1)  # idle again

    def test_mesh_and_calibration_from_numpy(self):
        scene = insitu.Scene(DEMO)
        scene.set("render.spp", 1)
        camera = scene.camera
        K = np.array([[camera["fx"], 0, camera["cx"]], [0, camera["fy"], camera["cy"]], [0, 0, 1]])
        xyz = np.array([[0, 0, 0], [1, 0, 0], [1, 0, -1], [0, 0, -1], [0.5, 0.9, -0.5], [-0.5, 0.4, -1.5]], float)
        p_cam = xyz @ camera["R_cam_from_world"].T + np.array(camera["t_cam_from_world"])
        uv = (p_cam @ K.T)[:, :2] / p_cam[:, 2:]
        calibration = insitu.Calibration(np.hstack([uv, xyz]), camera["width"], camera["height"], model="f")
        self.assertLess(calibration.rms_px, 1e-6)
        self.assertAlmostEqual(calibration.camera["fx"], camera["fx"], delta=1e-6 * camera["fx"])
        scene.set_control_points(np.hstack([uv, xyz]))
        self.assertIn("RMS", scene.calibration_report)
        # A floating quad from numpy: it covers pixels the objects did not.
        before = scene.render().layers["objects"][..., 3]
        quad = np.array([[-0.3, 0.6, -0.3], [0.3, 0.6, -0.3], [0.3, 1.2, -0.3], [-0.3, 1.2, -0.3]], np.float32)
        scene.add_mesh(quad, np.array([[0, 1, 2], [0, 2, 3]]), kd=(0.2, 0.5, 0.2), name="panel")
        after = scene.render().layers["objects"][..., 3]
        self.assertGreater((after > before + 0.5).sum(), 100)
        with self.assertRaises(insitu.Error) as e:
            scene.add_mesh(quad, np.array([[0, 1, 7]]), name="panel")
        self.assertEqual(str(e.exception), "panel: indices[2]: vertex 7 out of range (the mesh has 4 vertices)")

    def test_readme_example_runs(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "minimal.png")
            run = subprocess.run([sys.executable, os.path.join(SOURCE, "examples", "minimal.py"), DEMO, out],
                                 capture_output=True, text=True)
            self.assertEqual(run.returncode, 0, run.stderr)
            self.assertIn("16 spp", run.stdout)
            self.assertTrue(os.path.exists(out))


if __name__ == "__main__":
    unittest.main()
