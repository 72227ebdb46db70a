# glstereo — the two set-up commands are `make demo` and `make test`.
# Both install the Debian packages they need when missing (as root, with apt).

CARGO    ?= cargo
PROFILE  ?= debug
LIBDIR   := $(CURDIR)/target/$(PROFILE)
OUT      ?= $(CURDIR)/out
CARGO_PROFILE_FLAG := $(if $(filter release,$(PROFILE)),--release,)

# Runtime: Mesa's EGL/GL/OSMesa (llvmpipe), Xvfb for the GLX tests.
# Build: the GL/EGL/OSMesa/GLUT headers for the C examples, pkg-config, a C compiler.
# Tests: valgrind (leak attribution through Mesa; gcc brings ASan/UBSan/LSan);
# the real clients of tests/clients.rs: GLFW, SDL2, PyOpenGL, libepoxy, Qt 5 and 6 (g++),
# OpenSceneGraph's osgshape, glxgears; the GL layers glstereo stacks with
# (apitrace, MangoHud, RenderDoc's renderdoccmd and in-app API header);
# Pillow and exiftool, the independent readers of the MPO/JPS stereo photos;
# lavapipe (Mesa's CPU Vulkan driver) for zink, the GL-over-Vulkan driver of
# tests/zink.rs.
# libXtst, with which tests/keys.rs types the live keys (XTEST), and libXi's
# headers for its XInput 2 client.
# EGL and Wayland (tests/egl.rs): GLES and wayland-egl headers for the
# oracle, weston (its headless backend is the Wayland server) and glmark2's
# GLX, EGL and Wayland builds, the real programs of tests/egl.rs and
# tests/auto_glmark2.rs. gcc-multilib: the 32-bit program of
# tests/preload_location.rs (glstereo-run picks the layer by word size).
DEB_PACKAGES := libegl1 libegl-mesa0 libgl1 libgl1-mesa-dri libglx-mesa0 libosmesa6 \
                libgl-dev libegl-dev libosmesa6-dev freeglut3-dev libx11-dev \
                xvfb x11-apps x11-utils xauth pkg-config gcc make valgrind \
                libx11-xcb-dev libglfw3-dev libsdl2-dev python3-opengl libepoxy-dev \
                qtbase5-dev qt6-base-dev libqt6opengl6-dev g++ \
                openscenegraph mesa-utils apitrace mangohud renderdoccmd librenderdoc-dev \
                python3-pil libimage-exiftool-perl mesa-vulkan-drivers \
                libxtst6 libxi-dev \
                libgles-dev libwayland-dev weston glmark2-x11 glmark2-es2-x11 \
                glmark2-wayland glmark2-es2-wayland gcc-multilib

.PHONY: all deps disk build header examples demo test check-sanitize check-fits lint bench clean install uninstall

all: build examples

# Installs the missing packages; a no-op when everything is present.
deps:
	@missing=""; for p in $(DEB_PACKAGES); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "install ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  if [ "$$(id -u)" != 0 ]; then \
	    echo "glstereo needs these Debian packages:$$missing"; \
	    echo "install them as root: apt-get install -y$$missing"; exit 1; \
	  fi; \
	  echo "installing:$$missing"; \
	  export DEBIAN_FRONTEND=noninteractive; \
	  apt-get -o DPkg::Lock::Timeout=300 install -y --no-install-recommends $$missing \
	  || { apt-get -o DPkg::Lock::Timeout=300 update && \
	       apt-get -o DPkg::Lock::Timeout=300 install -y --no-install-recommends $$missing; }; \
	fi

# `make test` from a clean tree writes about 4.1 GB under target/ (the
# debug and sanitizer builds, the release preload, the tests' scratch). On
# a disk that fills up half way the linker dies of SIGBUS, which says
# nothing of space: so stop first, and say so, when what is free (plus
# what target/ already holds) is under DISK_MB_SURE_FAIL, short of what
# the run needs whatever it reuses; warn below DISK_MB_NEEDED.
DISK_MB_NEEDED    ?= 4200
DISK_MB_SURE_FAIL ?= 3000
disk:
	@mkdir -p target; \
	free=$$(df -Pm target | awk 'NR == 2 { print $$4 }'); \
	held=$$(du -sm target | cut -f1); \
	if [ $$((free + held)) -lt $(DISK_MB_SURE_FAIL) ]; then \
	  echo "make test: only $$free MB free for target/ ($$held MB already there);"; \
	  echo "  a clean run writes about $(DISK_MB_NEEDED) MB: free some space and run it again"; \
	  exit 1; \
	elif [ $$((free + held)) -lt $(DISK_MB_NEEDED) ]; then \
	  echo "make test: warning: $$free MB free for target/ ($$held MB already there);"; \
	  echo "  a clean run writes about $(DISK_MB_NEEDED) MB (a link that dies of SIGBUS means a full disk)"; \
	fi

build: deps
	$(CARGO) build $(CARGO_PROFILE_FLAG)

# Regenerates include/glstereo.h from the Rust sources (commit the result).
header:
	GLSTEREO_WRITE_HEADER=1 $(CARGO) build $(CARGO_PROFILE_FLAG)

examples: build
	$(MAKE) -C c-examples LIBDIR=$(LIBDIR)

# Renders the C examples headless and writes the stereo images under out/.
demo: examples
	@OUT=$(OUT) LIBDIR=$(LIBDIR) sh c-examples/demo.sh

lint:
	$(CARGO) fmt --all -- --check
	$(CARGO) clippy $(CARGO_PROFILE_FLAG) --workspace --all-targets -- -D warnings
	RUSTDOCFLAGS="-D warnings" $(CARGO) doc $(CARGO_PROFILE_FLAG) --workspace --no-deps

# The bounded fuzz run of tests/fuzz.rs lasts this long (plain `cargo test`: 2 s).
FUZZ_SECONDS ?= 60

# check-sanitize runs the tests/sanitize.rs tests (named sanitized_*), which
# the full run then skips.
test: deps disk lint check-sanitize check-fits
	$(CARGO) build $(CARGO_PROFILE_FLAG) -p glstereo-preload
	GLSTEREO_FUZZ_SECONDS=$(FUZZ_SECONDS) $(CARGO) test $(CARGO_PROFILE_FLAG) --no-fail-fast -- --skip sanitized_

# Every output format fitted to every window size a user can make (each
# from 1x1 to 64x64, thin ones up to 4096, random ones up to 4096x4096), at
# every vector level the processor has, against the reference
# (src/output/fits.rs): many sizes, so an optimised build (a debug
# `cargo test` lists them as ignored).
check-fits:
	$(CARGO) test --release --lib output::fits

# The C examples, the misuse suites and the threads tests built with
# -fsanitize=address,undefined, run clean (tests/sanitize.rs); the GLX ones
# (legacy stereo, freeglut, the layer's misuse suite, GLX threads) under
# glstereo-run on a private Xvfb.
check-sanitize: deps
	$(CARGO) test $(CARGO_PROFILE_FLAG) --test sanitize

# --- install: `make install PREFIX=/usr/local` (DESTDIR for staging) -------
# The libraries (libglstereo.so with its soname, libglstereo.a,
# libglstereo_preload.so), the headers, glstereo.pc, glstereo-run and its
# manual. Built with INSTALL_PROFILE (default release); needs no root
# unless PREFIX does.
PREFIX          ?= /usr/local
DESTDIR         ?=
INSTALL_PROFILE ?= release
INSTALL_LIBDIR  ?= $(PREFIX)/lib
INSTALL_INCDIR  ?= $(PREFIX)/include
INSTALL_BINDIR  ?= $(PREFIX)/bin
INSTALL_MANDIR  ?= $(PREFIX)/share/man
# The preload library and its stubs (one directory: the layer opens the
# stubs beside itself); the Debian packages give them a private one.
INSTALL_PRELOADDIR ?= $(INSTALL_LIBDIR)
# A Rust target to build for instead of this machine's (make deb DEB_HOST_ARCH=i386).
INSTALL_TARGET  ?=
VERSION         := $(shell sed -n 's/^version = "\(.*\)"/\1/p' Cargo.toml | head -n 1)
INSTALL_BUILT   := $(CURDIR)/target/$(if $(INSTALL_TARGET),$(INSTALL_TARGET)/)$(if $(filter dev debug,$(INSTALL_PROFILE)),debug,$(INSTALL_PROFILE))
INSTALL_CARGO   := --profile $(if $(filter debug,$(INSTALL_PROFILE)),dev,$(INSTALL_PROFILE)) $(if $(INSTALL_TARGET),--target $(INSTALL_TARGET))

install:
	$(CARGO) build $(INSTALL_CARGO) -p glstereo -p glstereo-preload
	install -d $(DESTDIR)$(INSTALL_LIBDIR)/pkgconfig $(DESTDIR)$(INSTALL_INCDIR)/glstereo \
	  $(DESTDIR)$(INSTALL_BINDIR) $(DESTDIR)$(INSTALL_MANDIR)/man1 $(DESTDIR)$(INSTALL_PRELOADDIR)
	install -m 755 $(INSTALL_BUILT)/libglstereo.so $(DESTDIR)$(INSTALL_LIBDIR)/libglstereo.so.$(VERSION)
	ln -sf libglstereo.so.$(VERSION) $(DESTDIR)$(INSTALL_LIBDIR)/libglstereo.so.0
	ln -sf libglstereo.so.0 $(DESTDIR)$(INSTALL_LIBDIR)/libglstereo.so
	install -m 644 $(INSTALL_BUILT)/libglstereo.a $(DESTDIR)$(INSTALL_LIBDIR)/libglstereo.a
	install -m 755 $(INSTALL_BUILT)/libglstereo_preload.so $(DESTDIR)$(INSTALL_PRELOADDIR)/libglstereo_preload.so
	install -m 755 $(INSTALL_BUILT)/libglstereo_stub_GL.so $(INSTALL_BUILT)/libglstereo_stub_GLX.so \
	  $(INSTALL_BUILT)/libglstereo_stub_OpenGL.so $(INSTALL_BUILT)/libglstereo_stub_EGL.so \
	  $(INSTALL_BUILT)/libglstereo_stub_GLESv2.so $(DESTDIR)$(INSTALL_PRELOADDIR)/
	install -m 644 include/glstereo.h $(DESTDIR)$(INSTALL_INCDIR)/glstereo.h
	install -m 644 include/glstereo/*.h $(DESTDIR)$(INSTALL_INCDIR)/glstereo/
	sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@LIBDIR@|$(INSTALL_LIBDIR)|' \
	  -e 's|@INCLUDEDIR@|$(INSTALL_INCDIR)|' -e 's|@VERSION@|$(VERSION)|' \
	  glstereo.pc.in > $(DESTDIR)$(INSTALL_LIBDIR)/pkgconfig/glstereo.pc
	install -m 755 $(INSTALL_BUILT)/glstereo-run $(DESTDIR)$(INSTALL_BINDIR)/glstereo-run
	install -m 644 docs/glstereo-run.1 $(DESTDIR)$(INSTALL_MANDIR)/man1/glstereo-run.1

uninstall:
	rm -f $(DESTDIR)$(INSTALL_LIBDIR)/libglstereo.so.$(VERSION) \
	  $(DESTDIR)$(INSTALL_LIBDIR)/libglstereo.so.0 $(DESTDIR)$(INSTALL_LIBDIR)/libglstereo.so \
	  $(DESTDIR)$(INSTALL_LIBDIR)/libglstereo.a $(DESTDIR)$(INSTALL_PRELOADDIR)/libglstereo_preload.so \
	  $(DESTDIR)$(INSTALL_PRELOADDIR)/libglstereo_stub_GL.so $(DESTDIR)$(INSTALL_PRELOADDIR)/libglstereo_stub_GLX.so \
	  $(DESTDIR)$(INSTALL_PRELOADDIR)/libglstereo_stub_OpenGL.so \
	  $(DESTDIR)$(INSTALL_PRELOADDIR)/libglstereo_stub_EGL.so $(DESTDIR)$(INSTALL_PRELOADDIR)/libglstereo_stub_GLESv2.so \
	  $(DESTDIR)$(INSTALL_LIBDIR)/pkgconfig/glstereo.pc $(DESTDIR)$(INSTALL_INCDIR)/glstereo.h \
	  $(DESTDIR)$(INSTALL_BINDIR)/glstereo-run $(DESTDIR)$(INSTALL_MANDIR)/man1/glstereo-run.1
	rm -rf $(DESTDIR)$(INSTALL_INCDIR)/glstereo
# ----------------------------------------------------------------------------

# --- deb: Debian packages in target/debian/ (README, "Install") ------------
# debhelper through `dpkg-buildpackage -b` (debian/; -tc: its staging
# directories are removed afterwards), then lintian. The
# release build in target/ is made, or reused, by make install inside
# debian/rules. DEB_HOST_ARCH=i386 cross-builds the i386 packages (after
# `dpkg --add-architecture i386`; needs Rust's i686 target, added here).
# Installs what it needs as root, as `deps` does.
DEB_BUILD_ARCH := $(shell dpkg --print-architecture 2>/dev/null)
DEB_HOST_ARCH  ?= $(DEB_BUILD_ARCH)
DEB_OUT        := target/debian
DEB_CHANGES    := $(DEB_OUT)/glstereo_$(VERSION)_$(DEB_HOST_ARCH)
DEB_RUST_i386  := i686-unknown-linux-gnu
DEB_RUST_arm64 := aarch64-unknown-linux-gnu
DEB_CROSS      := $(filter-out $(DEB_BUILD_ARCH),$(DEB_HOST_ARCH))
# debian/control's Build-Depends: dpkg-shlibdeps reads the libraries the
# stubs link (libGL.so.1, libGLX.so.0, libOpenGL.so.0, libEGL.so.1,
# libGLESv2.so.2) from their installed packages.
DEB_LIBS       := libc6-dev libgl1 libglx0 libopengl0 libegl1 libgles2
DEB_TOOLS      := debhelper dpkg-dev lintian gcc \
                  $(if $(DEB_CROSS),crossbuild-essential-$(DEB_CROSS) $(DEB_LIBS:=:$(DEB_CROSS)),$(DEB_LIBS))

.PHONY: deb
deb:
	@if [ -n "$(DEB_CROSS)" ] && ! dpkg --print-foreign-architectures | grep -qx "$(DEB_CROSS)"; then \
	  echo "make deb: add the $(DEB_CROSS) architecture first: dpkg --add-architecture $(DEB_CROSS) && apt-get update"; exit 1; \
	fi
	@$(MAKE) --no-print-directory deps DEB_PACKAGES="$(DEB_TOOLS)"
	@command -v $(CARGO) >/dev/null || { \
	  echo "make deb: no cargo: install Rust 1.85 or newer with rustup (Debian 12's rustc is 1.63)"; exit 1; }
	@if [ -n "$(DEB_CROSS)" ]; then \
	  t="$(DEB_RUST_$(DEB_CROSS))"; \
	  [ -n "$$t" ] || { echo "make deb: no Rust target known for $(DEB_CROSS)"; exit 1; }; \
	  rustup target list --installed 2>/dev/null | grep -qx "$$t" || rustup target add "$$t" || { \
	    echo "make deb: Rust's $$t target is missing and rustup could not add it"; exit 1; }; \
	fi
	mkdir -p $(DEB_OUT)
	sh debian/make-meta.sh
	$(if $(DEB_CROSS),CC=$$(dpkg-architecture -a$(DEB_CROSS) -qDEB_HOST_GNU_TYPE)-gcc) \
	dpkg-buildpackage -b -tc --no-sign -a$(DEB_HOST_ARCH) \
	  --buildinfo-file=$(DEB_CHANGES).buildinfo --buildinfo-option=-u$(DEB_OUT) \
	  --changes-file=$(DEB_CHANGES).changes --changes-option=-u$(DEB_OUT)
	lintian --fail-on error $(DEB_CHANGES).changes
	@ls -l $(DEB_OUT)/*_$(VERSION)_$(DEB_HOST_ARCH).deb

# Benchmarks (release build; see BENCHMARKS.md): the frame loop, mono vs
# stereo on EGL, OSMesa and GLX (a private Xvfb), light and heavy scenes;
# the same with both eyes captured to PNG every frame; then every output
# mode's CPU and GL composition against a memcpy (criterion); stereo photo
# encoding against PNG.
bench:
	$(CARGO) bench --bench frame_loop
	$(CARGO) bench --bench frame_loop -- --scene light --capture --no-control
	$(CARGO) bench --bench compose
	$(CARGO) bench --bench stereo_photo
	$(CARGO) build --release -p glstereo-preload
	sh benches/glx_frame_loop.sh
	sh benches/glx_shader_outputs.sh

clean:
	$(CARGO) clean
	$(MAKE) -C c-examples clean
	rm -rf $(OUT)
