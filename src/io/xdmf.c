/* xdmf.c: run.xdmf, the XDMF 3 temporal collection of one Polyvertex grid
 * per frame over the datasets of run.h5, and the parts of run.h5 that only
 * it reads: /xdmf/vertex_NNNNNN, the connectivity 0 .. n-1 (shared by
 * consecutive frames of n points), and /xdmf/xy_NNNNNN (xyz_NNNNNN in 3D),
 * the n x 2 (n x 3) virtual view of a frame's positions; and bodies.xdmf,
 * the same collection of the rigid bodies' outlines, for runs with bodies
 * (bodies_out.c writes their datasets). Each file is kept complete after
 * each frame: the frame's grid goes in before the closing tags, which are
 * written again. */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <hdf5.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "io/h5err.h"
#include "io/io.h"
#include "io/output_internal.h"

/* The head of a temporal collection named `name`, and the tail of every
 * file. */
static const char xdmf_head[] =
    "<?xml version=\"1.0\" ?>\n"
    "<Xdmf Version=\"3.0\" xmlns:xi=\"http://www.w3.org/2001/XInclude\">\n"
    "  <Domain>\n"
    "    <Grid Name=\"%s\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
static const char xdmf_tail[] = "    </Grid>\n  </Domain>\n</Xdmf>\n";

/* path as an empty temporal collection of grids `name`: *f open, *tail the
 * offset of the closing tags. */
static int open_collection(FILE **f, long *tail, const char *path, const char *name, mpm_err *err)
{
  char head[sizeof xdmf_head + 32];
  snprintf(head, sizeof head, xdmf_head, name);
  int rc = mpm_io_out_open_text(f, path, head, err);
  if (rc != MPM_OK)
    return rc;
  *tail = ftell(*f);
  if (*tail < 0 || fputs(xdmf_tail, *f) < 0 || fflush(*f) != 0)
    return mpm_err_set(err, MPM_EIO, "cannot write '%s': %s", path, strerror(errno));
  return MPM_OK;
}

/* run.xdmf starts as an empty temporal collection; frames are inserted
 * before the closing tags, which are rewritten after each frame. A
 * bodies.xdmf of an earlier run in the directory goes: the first frame with
 * outlines makes a new one. */
int mpm_io_out_xdmf_open(mpm_io_output *out, mpm_err *err)
{
  if (out->bxdmf && fclose(out->bxdmf) != 0)
    return mpm_err_set(err, MPM_EIO, "cannot close '%s': %s", out->bxdmf_path, strerror(errno));
  out->bxdmf = NULL;
  if (unlink(out->bxdmf_path) != 0 && errno != ENOENT)
    return mpm_err_set(err, MPM_EIO, "cannot remove '%s': %s", out->bxdmf_path, strerror(errno));
  return open_collection(&out->xdmf, &out->xdmf_tail_pos, out->xdmf_path, "points", err);
}

/* run.xdmf written again for frames 0 .. nframes-1 of run.h5. */
int mpm_io_out_xdmf_rebuild(mpm_io_output *out, long nframes, const mpm_io_h5_quiet *q,
                            mpm_err *err)
{
  int rc = mpm_io_out_xdmf_open(out, err);
  for (long k = 0; rc == MPM_OK && k < nframes; k++) {
    char name[32];
    unsigned long long n = 0;
    double t = 0.0;
    int dim = -1;
    snprintf(name, sizeof name, "%06ld", k);
    hid_t g = H5Gopen2(out->frames, name, H5P_DEFAULT);
    if (g < 0 || mpm_io_h5_attr_read(g, "time", H5T_NATIVE_DOUBLE, &t) < 0 ||
        mpm_io_h5_attr_read(g, "npoints", H5T_NATIVE_ULLONG, &n) < 0 ||
        (dim = mpm_io_frame_dim(g)) < 0)
      rc = mpm_io_h5_fail(err, q, "cannot read the frames of", out->h5_path);
    mpm_io_h5_close(g);
    snprintf(name, sizeof name, "vertex_%06ld", k);
    if (rc == MPM_OK && H5Lexists(out->xdmf_group, name, H5P_DEFAULT) > 0) {
      out->vertex_frame = (int)k;
      out->vertex_n = (size_t)n;
    }
    out->nframes = (int)k;
    if (rc == MPM_OK && mpm_io_out_outline_counts(out, k) < 0)
      rc = mpm_io_h5_fail(err, q, "cannot read the body outlines of", out->h5_path);
    if (rc == MPM_OK)
      rc = mpm_io_out_xdmf_frame(out, t, (size_t)n, dim, err);
  }
  out->nframes = (int)nframes;
  return rc;
}

/* Polyvertex connectivity 0..n-1, written again only when n changes. */
int mpm_io_out_vertices(mpm_io_output *out, size_t n, const mpm_io_h5_quiet *q, mpm_err *err)
{
  char name[32];
  int *v;
  herr_t rc;
  if (n == 0 || (out->vertex_frame >= 0 && out->vertex_n == n))
    return MPM_OK;
  v = malloc(n * sizeof *v);
  if (!v)
    return mpm_err_set(err, MPM_ENOMEM, "out of memory writing frame %d", out->nframes);
  for (size_t i = 0; i < n; i++)
    v[i] = (int)i;
  snprintf(name, sizeof name, "vertex_%06d", out->nframes);
  rc = mpm_io_h5_write_array(out->xdmf_group, name, H5T_STD_I32LE, H5T_NATIVE_INT, n, v, NULL,
                   "Polyvertex connectivity of run.xdmf");
  free(v);
  if (rc < 0)
    return mpm_io_h5_fail(err, q, "cannot write connectivity to", out->h5_path);
  out->vertex_n = n;
  out->vertex_frame = out->nframes;
  return MPM_OK;
}

/* /xdmf/xy_NNNNNN: an n x 2 virtual dataset whose columns are the frame's x
 * and y datasets, so readers that want interleaved XY points get them
 * without a second copy of the positions; /xdmf/xyz_NNNNNN, n x 3 with z,
 * for a 3D frame (dim = 3). */
herr_t mpm_io_out_xy_view(hid_t xg, int frame, size_t n, int dim)
{
  hsize_t vdims[2] = {(hsize_t)n, (hsize_t)dim}, sdims[1] = {(hsize_t)n};
  hsize_t start[2] = {0, 0}, count[2] = {(hsize_t)n, 1};
  hid_t vspace = H5Screate_simple(2, vdims, NULL);
  hid_t sspace = H5Screate_simple(1, sdims, NULL);
  hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  hid_t dset = H5I_INVALID_HID;
  herr_t rc = (vspace < 0 || sspace < 0 || dcpl < 0) ? -1 : 0;
  char src[48], name[32];
  for (int c = 0; c < dim && rc >= 0; c++) {
    start[1] = (hsize_t)c;
    snprintf(src, sizeof src, "/frames/%06d/%s", frame, c == 0 ? "x" : c == 1 ? "y" : "z");
    rc = H5Sselect_hyperslab(vspace, H5S_SELECT_SET, start, NULL, count, NULL);
    if (rc >= 0)
      rc = H5Pset_virtual(dcpl, vspace, ".", src, sspace);
  }
  snprintf(name, sizeof name, dim == 3 ? "xyz_%06d" : "xy_%06d", frame);
  if (rc >= 0)
    dset = H5Dcreate2(xg, name, H5T_IEEE_F64LE, vspace, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  if (rc >= 0 && dset < 0)
    rc = -1;
  mpm_io_h5_close(dset);
  mpm_io_h5_close(dcpl);
  mpm_io_h5_close(sspace);
  mpm_io_h5_close(vspace);
  return rc;
}

/* One <DataItem> referring to dataset path (relative to run.h5) of n values. */
static void xdmf_item(FILE *f, const char *path, size_t n, int isint, const char *indent)
{
  fprintf(f,
          "%s<DataItem Dimensions=\"%zu\" NumberType=\"%s\" Precision=\"%d\" "
          "Format=\"HDF\">run.h5:%s</DataItem>\n",
          indent, n, isint ? "Int" : "Float", isint ? 4 : 8, path);
}

/* Geometry "XY" from one n x 2 array, the frame's virtual XY view: ParaView
 * (5.11) opens it with all three of its XDMF readers (XDMF, Xdmf3 S/T) and
 * sets z = 0. Geometries assembled from the separate x and y datasets do not
 * work there: "X_Y" and a JOIN function crash the Xdmf3 readers and "X_Y_Z"
 * loses the points; only the legacy XDMF reader understands them. A 3D
 * frame (dim = 3) has geometry "XYZ" from its n x 3 view likewise. */
static void xdmf_grid(FILE *f, const mpm_io_output *out, double t, size_t n, int dim)
{
  char path[64];
  fprintf(f, "      <Grid Name=\"frame_%06d\" GridType=\"Uniform\">\n", out->nframes);
  fprintf(f, "        <Time Value=\"%.17g\"/>\n", t);
  fprintf(f,
          "        <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"%zu\" "
          "NodesPerElement=\"1\">\n",
          n);
  snprintf(path, sizeof path, "/xdmf/vertex_%06d", out->vertex_frame);
  xdmf_item(f, path, n, 1, "          ");
  fprintf(f, "        </Topology>\n        <Geometry GeometryType=\"%s\">\n",
          dim == 3 ? "XYZ" : "XY");
  fprintf(f,
          "          <DataItem Dimensions=\"%zu %d\" NumberType=\"Float\" Precision=\"8\" "
          "Format=\"HDF\">run.h5:/xdmf/%s_%06d</DataItem>\n",
          n, dim, dim == 3 ? "xyz" : "xy", out->nframes);
  fprintf(f, "        </Geometry>\n");
  for (size_t k = 0; k < out->nfields; k++) {
    const field_spec *s = &out->fields[k];
    if (s->dim > dim)
      continue;
    fprintf(f, "        <Attribute Name=\"%s\" AttributeType=\"Scalar\" Center=\"Node\">\n",
            s->name);
    snprintf(path, sizeof path, "/frames/%06d/%s", out->nframes, s->name);
    xdmf_item(f, path, n, s->kind == FIELD_INT, "          ");
    fprintf(f, "        </Attribute>\n");
  }
  fprintf(f, "      </Grid>\n");
}

/* The frame's body outlines (bodies_out.c): a Mixed topology of closed
 * polylines (plane) or faces (3D), XYZ vertices, and the body of each cell;
 * ParaView's three XDMF readers open it (tests/paraview-bodies.sh). */
static void bodies_grid(FILE *f, const mpm_io_output *out, double t)
{
  char path[64];
  fprintf(f, "      <Grid Name=\"bodies_%06d\" GridType=\"Uniform\">\n", out->nframes);
  fprintf(f, "        <Time Value=\"%.17g\"/>\n", t);
  fprintf(f, "        <Topology TopologyType=\"Mixed\" NumberOfElements=\"%zu\">\n",
          out->outline_ncell);
  snprintf(path, sizeof path, "/xdmf/bodies_cells_%06d", out->nframes);
  xdmf_item(f, path, out->outline_len, 1, "          ");
  fprintf(f, "        </Topology>\n        <Geometry GeometryType=\"XYZ\">\n");
  fprintf(f,
          "          <DataItem Dimensions=\"%zu 3\" NumberType=\"Float\" Precision=\"8\" "
          "Format=\"HDF\">run.h5:/xdmf/bodies_xyz_%06d</DataItem>\n",
          out->outline_nv, out->nframes);
  fprintf(f, "        </Geometry>\n");
  fprintf(f, "        <Attribute Name=\"body\" AttributeType=\"Scalar\" Center=\"Cell\">\n");
  snprintf(path, sizeof path, "/xdmf/bodies_id_%06d", out->nframes);
  xdmf_item(f, path, out->outline_ncell, 1, "          ");
  fprintf(f, "        </Attribute>\n      </Grid>\n");
}

/* Insert a grid into the collection of file f (path) before its closing
 * tags at *tail: points (n, dim) or, with bodies set, the outlines. */
static int insert(FILE *f, long *tail, const char *path, const mpm_io_output *out, double t,
                  size_t n, int dim, int bodies, mpm_err *err)
{
  if (fseek(f, *tail, SEEK_SET) != 0)
    return mpm_err_set(err, MPM_EIO, "cannot seek in '%s': %s", path, strerror(errno));
  if (bodies)
    bodies_grid(f, out, t);
  else
    xdmf_grid(f, out, t, n, dim);
  *tail = ftell(f);
  if (*tail < 0 || fputs(xdmf_tail, f) < 0 || fflush(f) != 0 || ferror(f))
    return mpm_err_set(err, MPM_EIO, "cannot write '%s': %s", path, strerror(errno));
  return MPM_OK;
}

/* Insert the frame's grid into run.xdmf (none for a frame without points:
 * readers reject empty datasets) and, when the frame has body outlines,
 * theirs into bodies.xdmf (made at the first). */
int mpm_io_out_xdmf_frame(mpm_io_output *out, double t, size_t n, int dim, mpm_err *err)
{
  int rc = MPM_OK;
  if (n > 0)
    rc = insert(out->xdmf, &out->xdmf_tail_pos, out->xdmf_path, out, t, n, dim, 0, err);
  if (rc != MPM_OK || out->outline_frame != out->nframes)
    return rc;
  if (!out->bxdmf)
    rc = open_collection(&out->bxdmf, &out->bxdmf_tail_pos, out->bxdmf_path, "bodies", err);
  if (rc == MPM_OK)
    rc = insert(out->bxdmf, &out->bxdmf_tail_pos, out->bxdmf_path, out, t, 0, 3, 1, err);
  return rc;
}
