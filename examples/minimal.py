import sys
import insitu

scene = insitu.Scene(sys.argv[1])            # minimal.py SCENE.json OUT.png
scene.set("render.spp", 16)
result = scene.render(progress=lambda p: p["noise"] >= 0 and print(f"{p['spp_done']} spp"))
result.write(sys.argv[2])
alpha = result.layers["objects"][..., 3]     # numpy, (height, width)
print(f"{result.width}x{result.height}, {result.spp} spp, objects cover {alpha.mean():.1%}")
