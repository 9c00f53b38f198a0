/* filter_and_predict.c — a C host of libroprec_c (plugin/c/roprec.h).
 *
 *   filter_and_predict CELL.xml [PROGRAM [HOLES.csv]]
 *
 * 1. Opens the cell and filters one target: the first sample hole, T001 of
 *    samples/emotor-housing/holes.csv (150, 0, 250 mm in the workobject, drilled along -z). Its
 *    TCP pose in the robot base frame is the workobject (1350, 0, 300 mm, no rotation) times the
 *    hole frame (x along the workobject x, z = drilling direction).
 * 2. Checks the filtered target: programmed position + predicted deviation = the wanted position.
 * 3. With PROGRAM: predicts the whole job and prints the summary JSON.
 *
 * Build (installed roprec under P):  cc filter_and_predict.c -I P/include -L P/lib -lroprec_c -lm
 * Exit code: the first non-zero status of the roprec calls; 1 if the check of step 2 fails. */
#include <math.h>
#include <stdio.h>

#include <roprec/roprec.h>

int main(int argc, char** argv) {
  char err[1024];
  roprec_session* s = NULL;
  /* T001, row-major, mm; rotation diag(1, -1, -1): TCP z points down into the top face. */
  /* clang-format off */
  const double wanted[16] = {1, 0, 0, 1500.0,
                             0, -1, 0, 0.0,
                             0, 0, -1, 550.0,
                             0, 0, 0, 1};
  /* clang-format on */
  double programmed[16];
  double joints[6];
  double deviation[6];
  double U_work_um = 0;
  double miss_um = 0;
  int i;
  int rc;

  if (argc < 2 || argc > 4) {
    fprintf(stderr, "usage: %s CELL.xml [PROGRAM [HOLES.csv]]\n", argv[0]);
    return 2;
  }
  printf("roprec %s\n", roprec_version());
  rc = roprec_open(argv[1], &s, err, sizeof err);
  if (rc != ROPREC_OK) {
    fprintf(stderr, "roprec_open: %s\n", err);
    return rc;
  }

  rc = roprec_filter_target(s, wanted, NULL, programmed, joints, err, sizeof err);
  if (rc != ROPREC_OK) {
    fprintf(stderr, "roprec_filter_target: %s\n", err);
    roprec_close(s);
    return rc;
  }
  printf("program  x y z = %.6f %.6f %.6f mm (wanted %.3f %.3f %.3f)\n", programmed[3],
         programmed[7], programmed[11], wanted[3], wanted[7], wanted[11]);
  printf("joints   %.4f %.4f %.4f %.4f %.4f %.4f deg\n", joints[0], joints[1], joints[2], joints[3],
         joints[4], joints[5]);

  rc = roprec_predict_joints(s, joints, deviation, &U_work_um, err, sizeof err);
  if (rc != ROPREC_OK) {
    fprintf(stderr, "roprec_predict_joints: %s\n", err);
    roprec_close(s);
    return rc;
  }
  for (i = 0; i < 3; ++i) {
    const double d = programmed[4 * i + 3] + deviation[i] * 1e-3 - wanted[4 * i + 3];
    miss_um += d * d * 1e6;
  }
  miss_um = sqrt(miss_um);
  printf("deviation at the programmed joints: %.3f %.3f %.3f um, U_work %.1f um\n", deviation[0],
         deviation[1], deviation[2], U_work_um);
  printf("predicted real TCP misses the wanted one by %.6f um\n", miss_um);
  roprec_close(s);

  if (argc >= 3) {
    char summary[ROPREC_SUMMARY_LEN];
    rc = roprec_predict_file(argv[1], argv[2], argc == 4 ? argv[3] : NULL, NULL, summary,
                             sizeof summary, err, sizeof err);
    if (rc == ROPREC_BAD_INPUT) {
      fprintf(stderr, "roprec_predict_file: %s\n", err);
      return rc;
    }
    printf("job summary: %s\n", summary);
    if (rc == ROPREC_ITEM_FAILED) fprintf(stderr, "some holes were not predicted:\n%s\n", err);
  }
  return miss_um < 0.1 ? rc : 1;
}
