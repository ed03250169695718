/* bands.c: points binned by bands of unit rows (mesh.h, mpm_mesh_bands).
 *
 * A loop over points that adds each point's share to the rows around it
 * (nodes or units) runs on many threads without two of them writing the same
 * row at once when it takes the points band by band: a band is h >= lo + hi
 * consecutive unit rows, so the rows written by two bands that are not
 * neighbours never meet, and the bands of one colour (every second band) can
 * run in parallel, the colours one after the other. Every written entry then
 * sums its shares band by band and, within a band, in point order: the same
 * order whatever the number of threads and whichever thread takes a band.
 * The binning is a stable counting sort of the point indices by band, on
 * all threads. */
#include "mesh/mesh.h"

#include <limits.h>
#include <stdlib.h>

#ifdef _OPENMP
#include <omp.h>
#endif

mpm_mesh_bands *mpm_mesh_bands_alloc(void)
{
  return calloc(1, sizeof(mpm_mesh_bands));
}

void mpm_mesh_bands_free(mpm_mesh_bands *b)
{
  if (!b)
    return;
  free(b->start);
  free(b->idx);
  free(b->band_of_row);
  free(b->tcount);
  free(b);
}

/* Band height and count for ny unit rows: h = max(1, lo + hi) rows, the
 * remainder joining the last band; on a periodic axis an even count (the
 * last two bands merge when it is odd), so the colours alternate round it;
 * one band when the rows are too few for two. One colour when lo + hi = 0
 * (each row writes only to itself). */
static void band_layout(mpm_mesh_bands *b, int ny, int periodic, int lo, int hi)
{
  int h = lo + hi > 1 ? lo + hi : 1;
  int nb = ny / h;
  if (nb < 1)
    nb = 1;
  b->ncolour = lo + hi > 0 ? 2 : 1;
  if (b->ncolour == 2 && periodic && nb % 2 == 1)
    nb = nb > 1 ? nb - 1 : 1;
  if (b->ncolour == 2 && periodic && nb == 1)
    b->ncolour = 1;               /* one band wraps onto itself: one thread takes it */
  b->h = h;
  b->nb = nb;
  b->ny = ny;
  for (int j = 0; j < ny; j++) {
    const int k = j / h;
    b->band_of_row[j] = k < nb ? k : nb - 1;
  }
}

int mpm_mesh_bands_sort(mpm_mesh_bands *b, int ny, int periodic, int lo, int hi, size_t n,
                        const int *row, mpm_err *err)
{
  if (n > (size_t)INT_MAX)
    return mpm_err_set(err, MPM_ENOMEM, "bands: %zu points, at most %d", n, INT_MAX);
  if (ny > b->rcap) {
    int *r = realloc(b->band_of_row, (size_t)ny * sizeof *r);
    int *st = realloc(b->start, ((size_t)ny + 1) * sizeof *st);
    if (r)
      b->band_of_row = r;
    if (st)
      b->start = st;
    if (!r || !st)
      return mpm_err_set(err, MPM_ENOMEM, "bands: no memory for %d rows", ny);
    b->rcap = ny;
  }
  if (n > b->cap) {
    int *ix = realloc(b->idx, n * sizeof *ix);
    if (!ix)
      return mpm_err_set(err, MPM_ENOMEM, "bands: no memory for %zu points", n);
    b->idx = ix;
    b->cap = n;
  }
  if (b->ny != ny || b->lo != lo || b->hi != hi) {
    band_layout(b, ny, periodic, lo, hi);
    b->lo = lo;
    b->hi = hi;
  }
  int nt = 1;
#ifdef _OPENMP
  nt = n >= 256 ? omp_get_max_threads() : 1;     /* a few points: no fork */
#endif
  const size_t need = (size_t)nt * ((size_t)b->nb + 1);
  if (need > b->tcap) {
    int *tc = realloc(b->tcount, need * sizeof *tc);
    if (!tc)
      return mpm_err_set(err, MPM_ENOMEM, "bands: no memory for %d threads' counts", nt);
    b->tcount = tc;
    b->tcap = need;
  }
  /* A stable counting sort on the threads: each counts the points of its
   * share per band, the shares are laid out band by band in thread order
   * (so in point order), and each thread places its own points. The result,
   * the unique stable order, does not depend on the number of threads. */
  int *start = b->start;
  const int nb = b->nb;
#pragma omp parallel num_threads(nt) if (nt > 1)
  {
    int t = 0, nth = 1;
#ifdef _OPENMP
    t = omp_get_thread_num();
    nth = omp_get_num_threads();
#endif
    const size_t a = n * (size_t)t / (size_t)nth, e = n * ((size_t)t + 1) / (size_t)nth;
    int *cnt = b->tcount + (size_t)t * ((size_t)nb + 1);
    for (int k = 0; k < nb; k++)
      cnt[k] = 0;
    for (size_t p = a; p < e; p++)               /* this share's points per band */
      cnt[b->band_of_row[row[p]]]++;
#pragma omp barrier
#pragma omp single
    {
      int at = 0;                                /* first slot of band k, share u */
      for (int k = 0; k < nb; k++) {
        start[k] = at;
        for (int u = 0; u < nth; u++) {
          int *c = b->tcount + (size_t)u * ((size_t)nb + 1) + k;
          const int nk = *c;
          *c = at;
          at += nk;
        }
      }
      start[nb] = at;
    }
    for (size_t p = a; p < e; p++)               /* stable: point order within a band */
      b->idx[cnt[b->band_of_row[row[p]]]++] = (int)p;
  }
  b->n = n;
  return MPM_OK;
}
