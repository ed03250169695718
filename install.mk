# install.mk: what `make install` puts where (included by Makefile.am).
#
#   $(bindir)         granmpm, and the scripts as granmpm-NAME (kit_scripts):
#                     granmpm-run-once, granmpm-sweep-jam, -sweep-silo,
#                     -sweep-incline, -sweep-hstop, -sweep-collapse,
#                     granmpm-bench, granmpm-bench-diffusion, granmpm-example,
#                     granmpm-figures (figures/make-all)
#   $(pkglibexecdir)  ngf1d, the 1D reference (verification/ngf1d/local.mk)
#   $(pkgdatadir)     inputs/*.conf; figures/ (the drivers, their gnuplot
#                     scripts, helpers and captions); verification/ (the
#                     scripts of the cases that figure drivers run)
#   $(docdir)         README.md, docs/*.md, figures/README.md, each
#                     verification case's README.md, examples/ (all of it)
#   $(man1dir)        granmpm.1 (docs/granmpm.1.in; tests/man-help.sh keeps it
#                     in step with --help)
#
# The lists follow the tree (kit_data_list, kit_doc_list): a new input,
# figure driver, document or example is installed without a change here.
#
# One copy of each script. In the tree a script finds granmpm, its data and
# the other scripts from the tree's root, $src (`$(cd "$(dirname "$0")/.."
# && pwd)`, `/../..` from verification/CASE/), unless GRANMPM_SRCDIR,
# GRANMPM or GRANMPM_BUILDDIR say otherwise:
#   $src/src/app/granmpm (or $build/...)           the program
#   $src/scripts/NAME                               another script
#   $src/inputs/..., $src/figures/..., $src/verification/...  data
#   $GRANMPM_BUILDDIR/verification/ngf1d/ngf1d (or $build/...)  ngf1d
# The installed copy is the same file with these rewritten by kit_edit: the
# root becomes $(pkgdatadir) (where the data keep their places), the program
# $(bindir)/granmpm, a script $(bindir)/granmpm-NAME (in comments too, so its
# --help names it), ngf1d $(pkglibexecdir)/ngf1d. A tree path left in an
# installed file (kit_guard) fails the install: a new form of path needs a
# rule here.

# ---- the kit: lists ------------------------------------------------------

# Scripts installed in $(bindir) as granmpm-NAME: NAME:SOURCE.
kit_scripts = run-once:scripts/run-once \
	sweep-jam:scripts/sweep-jam sweep-silo:scripts/sweep-silo \
	sweep-incline:scripts/sweep-incline sweep-hstop:scripts/sweep-hstop \
	sweep-collapse:scripts/sweep-collapse \
	bench:scripts/bench bench-diffusion:scripts/bench-diffusion \
	example:scripts/example figures:figures/make-all

# Scripts of verification cases that the figure drivers run.
kit_verification_scripts = V7-ngf-chute/profile V8-vertical-chute/check \
	V8-vertical-chute/case

# Files of the tree installed under $(pkgdatadir), one a line (shell).
kit_data_list = cd '$(srcdir)' && { \
	find inputs -type f -name '*.conf'; \
	find figures -type f ! -name make-all ! -name README.md ! -name index.md; \
	for f in $(kit_verification_scripts); do echo "verification/$$f"; done; \
	} | LC_ALL=C sort

# Files of the tree installed under $(docdir), one a line (shell).
kit_doc_list = cd '$(srcdir)' && { \
	echo README.md; \
	find docs -type f -name '*.md'; \
	echo figures/README.md; \
	find verification -type f -name README.md; \
	if test -d examples; then find examples -type f; fi; \
	} | LC_ALL=C sort

# ---- the kit: the installed paths ----------------------------------------

kit_edit = sed \
	-e 's|\$$(cd "\$$(dirname "\$$0")/\.\." && pwd)|$(pkgdatadir)|g' \
	-e 's|\$$(cd "\$$(dirname "\$$0")/\.\./\.\." && pwd)|$(pkgdatadir)|g' \
	-e 's|\$$(cd "\$$(dirname "\$$GRANMPM")/\.\./\.\." && pwd)|$(pkglibexecdir)|g' \
	-e 's|\$$src/src/app/granmpm|$(bindir)/granmpm|g' \
	-e 's|\$$build/src/app/granmpm|$(bindir)/granmpm|g' \
	-e 's|\$$src/scripts/|$(bindir)/granmpm-|g' \
	-e 's|\$$GRANMPM_BUILDDIR/verification/ngf1d/ngf1d|$(pkglibexecdir)/ngf1d|g' \
	-e 's|\$$build/verification/ngf1d/ngf1d|$(pkglibexecdir)/ngf1d|g' \
	-e '/^\#/s|\([ (`]\)scripts/\([a-z]\)|\1granmpm-\2|g' \
	-e '/^\#/s|^\(\# *\)scripts/\([a-z]\)|\1granmpm-\2|' \
	-e '/^\#/s|\([ (`]\)figures/make-all|\1granmpm-figures|g' \
	-e '/^\#/s|^\(\# *\)figures/make-all|\1granmpm-figures|'

# Lines of an edited file that still name a place in the tree.
kit_guard = grep -n -e 'dirname "\$$0")/\.\.' -e 'dirname "\$$GRANMPM")' \
	-e '/src/app/granmpm' -e '\$$[a-z]*/scripts/' -e '/verification/ngf1d/ngf1d'

# kit_put SOURCE DEST: install SOURCE (in the tree) as DEST, edited,
# executable if SOURCE is (a shell function for the recipes below).
kit_put = kit_put() { \
	  $(kit_edit) "$$1" > "$$kit_tmp/f" || return 1; \
	  if $(kit_guard) "$$kit_tmp/f"; then \
	    echo "install: $$1 still names the source tree (see install.mk)" >&2; return 1; \
	  fi; \
	  if test -x "$$1"; then inst='$(INSTALL_SCRIPT)'; else inst='$(INSTALL_DATA)'; fi; \
	  echo " $$inst $$1 $$2 (kit_edit)"; \
	  $$inst "$$kit_tmp/f" "$$2"; \
	}; \
	kit_tmp=`mktemp -d "$${TMPDIR:-/tmp}/granmpm-install.XXXXXX"` || exit 1; \
	trap 'rm -rf "$$kit_tmp"' EXIT

# ---- the manual page --------------------------------------------------

man_MANS = granmpm.1
CLEANFILES += granmpm.1
granmpm.1: $(srcdir)/docs/granmpm.1.in Makefile
	$(AM_V_GEN)sed -e 's|@PACKAGE_VERSION[@]|$(PACKAGE_VERSION)|g' \
	  -e 's|@bindir[@]|$(bindir)|g' -e 's|@pkgdatadir[@]|$(pkgdatadir)|g' \
	  -e 's|@pkglibexecdir[@]|$(pkglibexecdir)|g' -e 's|@docdir[@]|$(docdir)|g' \
	  '$(srcdir)/docs/granmpm.1.in' > $@.tmp && mv $@.tmp $@

# ---- the kit: install and uninstall --------------------------------------

install-exec-local: install-kit-scripts
install-data-local: install-kit-data install-kit-docs
uninstall-local: uninstall-kit

install-kit-scripts:
	@$(NORMAL_INSTALL)
	@$(kit_put); set -e; \
	$(MKDIR_P) '$(DESTDIR)$(bindir)'; \
	for p in $(kit_scripts); do \
	  kit_put '$(srcdir)'/$${p#*:} '$(DESTDIR)$(bindir)'/granmpm-$${p%%:*}; \
	done

install-kit-data:
	@$(NORMAL_INSTALL)
	@$(kit_put); set -e; \
	files=`$(kit_data_list)`; \
	for f in $$files; do \
	  $(MKDIR_P) "$(DESTDIR)$(pkgdatadir)/`dirname $$f`"; \
	  kit_put '$(srcdir)'/$$f "$(DESTDIR)$(pkgdatadir)/$$f"; \
	done

install-kit-docs:
	@$(NORMAL_INSTALL)
	@set -e; files=`$(kit_doc_list)`; \
	for f in $$files; do \
	  $(MKDIR_P) "$(DESTDIR)$(docdir)/`dirname $$f`"; \
	  if test -x '$(srcdir)'/$$f; then inst='$(INSTALL_SCRIPT)'; else inst='$(INSTALL_DATA)'; fi; \
	  echo " $$inst $$f '$(DESTDIR)$(docdir)/$$f'"; \
	  $$inst '$(srcdir)'/$$f "$(DESTDIR)$(docdir)/$$f"; \
	done

# kit_rm BASE LIST: remove the files of LIST (kit_data_list, kit_doc_list)
# under BASE, then the folders that leaves empty, the deepest first, and BASE.
kit_rm = kit_rm() { \
	  echo " rm -f the kit's files in '$$1'"; \
	  dirs=; \
	  for f in $$2; do \
	    rm -f "$$1/$$f"; \
	    d=`dirname $$f`; \
	    while test "$$d" != .; do dirs="$$dirs $$d"; d=`dirname $$d`; done; \
	  done; \
	  for d in `for d in $$dirs; do echo $$d; done | LC_ALL=C sort -ru`; do \
	    rmdir "$$1/$$d" 2>/dev/null || :; \
	  done; \
	  rmdir "$$1" 2>/dev/null || :; \
	}

uninstall-kit:
	@$(NORMAL_UNINSTALL)
	@for p in $(kit_scripts); do \
	  echo " rm -f '$(DESTDIR)$(bindir)/granmpm-$${p%%:*}'"; \
	  rm -f "$(DESTDIR)$(bindir)/granmpm-$${p%%:*}"; \
	done
	@$(kit_rm); kit_rm '$(DESTDIR)$(pkgdatadir)' "`$(kit_data_list)`"
	@$(kit_rm); kit_rm '$(DESTDIR)$(docdir)' "`$(kit_doc_list)`"

.PHONY: install-kit-scripts install-kit-data install-kit-docs uninstall-kit

# ---- make installcheck ---------------------------------------------------
# The installed kit alone: from an empty directory, with the variables that
# would point the scripts at a tree (GRANMPM, GRANMPM_SRCDIR,
# GRANMPM_BUILDDIR) unset, granmpm-example runs 0.2 s of the example (and
# draws it when gnuplot is there), granmpm-sweep-hstop makes a sweep of two
# tiny runs (two depths of the quick NGF chute at 27 deg, 60 ms each) through
# granmpm-run-once and collects it, granmpm-figures lists its drivers, and
# the manual page is in place. The sweep is left out without GNU parallel.
installcheck-local:
	@unset GRANMPM GRANMPM_SRCDIR GRANMPM_BUILDDIR; \
	OMP_NUM_THREADS=1; export OMP_NUM_THREADS; \
	tmp=`mktemp -d "$${TMPDIR:-/tmp}/granmpm-installcheck.XXXXXX"` || exit 1; \
	trap 'rm -rf "$$tmp"' EXIT; \
	cd "$$tmp" || exit 1; \
	pass=0; fail=0; \
	ok() { echo "PASS: installcheck: $$1"; pass=`expr $$pass + 1`; }; \
	bad() { echo "FAIL: installcheck: $$1"; fail=`expr $$fail + 1`; }; \
	echo "installcheck: in the empty directory $$tmp"; \
	if '$(bindir)/granmpm-example' example --set time.t_end=0.2 --quiet > example.log 2>&1 \
	   && test "`'$(bindir)/granmpm' info example --status`" = finished \
	   && test -s example/diagnostics.csv && test -s example/final-state.csv \
	   && { test -s example/final-state.png || ! command -v gnuplot > /dev/null; }; \
	then ok "granmpm-example"; else bad "granmpm-example"; cat example.log; fi; \
	if command -v parallel > /dev/null; then \
	  if '$(bindir)/granmpm-sweep-hstop' --out sweep \
	       --input '$(pkgdatadir)/inputs/ngf-chute-quick.conf' --angles 27 \
	       --ratios '0.7 1.1' --t-end 0.06 --t-min 0.01 --jobs 1 > sweep.log 2>&1 \
	     && test `grep -c '^27,' sweep/hstop.csv` -eq 2 && ! grep -q failed sweep/hstop.csv \
	     && test `ls sweep/runs/*/run.h5 | wc -l` -eq 2; \
	  then ok "granmpm-sweep-hstop, two runs"; else bad "granmpm-sweep-hstop"; cat sweep.log; fi; \
	else echo "SKIP: installcheck: granmpm-sweep-hstop (GNU parallel not found)"; fi; \
	if '$(bindir)/granmpm-figures' --list | grep -qx final-state; \
	then ok "granmpm-figures --list"; else bad "granmpm-figures --list"; fi; \
	if test -s '$(man1dir)/granmpm.1'; \
	then ok "$(man1dir)/granmpm.1"; else bad "$(man1dir)/granmpm.1"; fi; \
	echo "installcheck: $$pass passed, $$fail failed"; \
	test $$fail -eq 0
