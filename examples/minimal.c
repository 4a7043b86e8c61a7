#include <insitu/insitu.h>
#include <stdio.h>
int main(int argc, char** argv) {  /* minimal SCENE.json OUT.png */
  insitu_scene* scene = NULL;
  insitu_result* result = NULL;
  if (argc != 3 || insitu_scene_from_file(argv[1], &scene) != INSITU_OK ||
      insitu_scene_set(scene, "render.spp", "16") != INSITU_OK ||
      insitu_render(scene, NULL, NULL, &result) != INSITU_OK || insitu_result_write(result, argv[2], NULL) != INSITU_OK) {
    fprintf(stderr, "error: %s\n", argc == 3 ? insitu_last_error() : "usage: minimal SCENE OUT.png");
    return 2;
  }
  const float* rgba = NULL;  /* the objects' premultiplied RGB and coverage, owned by the result */
  const int w = insitu_result_width(result), h = insitu_result_height(result);
  double cover = 0;
  insitu_result_layer(result, "objects", &rgba, NULL);
  for (int i = 0; i < w * h; ++i) cover += rgba[4 * i + 3];
  printf("%dx%d, %d spp, objects cover %.1f%%\n", w, h, insitu_result_spp(result), 100 * cover / (w * h));
  insitu_result_free(result);
  insitu_scene_free(scene);
  return 0;
}
