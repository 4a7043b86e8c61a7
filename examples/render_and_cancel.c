/* The C API end to end: render a scene with progress, write the image and its layers, then start
 * a longer render and cancel it halfway from the progress callback (as a host's Cancel button
 * would, or insitu_scene_cancel from its UI thread).
 *
 *   render_and_cancel SCENE.json OUT.png
 *
 * Exit 0 when both went as expected, 2 on bad input (the message on stderr), 1 otherwise. */
#include <insitu/insitu.h>
#include <stdio.h>

static int show_progress(const insitu_progress* p, void* user) {
  (void)user;
  if (p->noise >= 0) /* after each pass */
    fprintf(stderr, "  %d/%d spp, noise %.1f%%, %.1f s, about %.1f s left\n", p->spp_done, p->spp_planned,
            100 * p->noise, p->seconds, p->seconds_left);
  return 0; /* go on */
}

static int cancel_halfway(const insitu_progress* p, void* user) {
  *(double*)user = p->fraction;
  return p->fraction >= 0.5; /* nonzero: cancel */
}

static int fail(insitu_scene* scene, insitu_result* result) {
  fprintf(stderr, "render_and_cancel: %s\n", insitu_last_error());
  insitu_result_free(result);
  insitu_scene_free(scene);
  return 2;
}

int main(int argc, char** argv) {
  if (argc != 3) {
    fprintf(stderr, "usage: render_and_cancel SCENE.json OUT.png\n");
    return 2;
  }
  printf("insitu %s (API %d)\n", insitu_version(), insitu_api_version());
  insitu_scene* scene = NULL;
  insitu_result* result = NULL;
  if (insitu_scene_from_file(argv[1], &scene) != INSITU_OK) return fail(scene, result);
  if (insitu_scene_set(scene, "render.spp", "8") != INSITU_OK) return fail(scene, result);
  if (insitu_render(scene, show_progress, NULL, &result) != INSITU_OK) return fail(scene, result);
  if (insitu_result_write(result, argv[2], NULL) != INSITU_OK) return fail(scene, result);
  printf("wrote %s: %dx%d, %d spp\n", argv[2], insitu_result_width(result), insitu_result_height(result),
         insitu_result_spp(result));
  insitu_result_free(result);
  result = NULL;

  /* The second render is cancelled at half way: INSITU_CANCELLED, with the samples taken. */
  double reached = 0;
  if (insitu_scene_set(scene, "render.spp", "256") != INSITU_OK) return fail(scene, result);
  const insitu_status status = insitu_render(scene, cancel_halfway, &reached, &result);
  if (status != INSITU_CANCELLED) {
    fprintf(stderr, "render_and_cancel: expected the second render to be cancelled (status %d)\n", (int)status);
    insitu_result_free(result);
    insitu_scene_free(scene);
    return 1;
  }
  printf("cancelled at %.0f%%: %d of 256 spp in every pixel\n", 100 * reached, insitu_result_spp(result));
  insitu_result_free(result);
  insitu_scene_free(scene);
  return 0;
}
