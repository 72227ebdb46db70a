# glstereo — the two set-up commands are `make demo` and `make test`.
# Both install the Debian packages they need when missing (as root, with apt).

CARGO    ?= cargo
PROFILE  ?= debug
LIBDIR   := $(CURDIR)/target/$(PROFILE)
OUT      ?= $(CURDIR)/out
CARGO_PROFILE_FLAG := $(if $(filter release,$(PROFILE)),--release,)

# Runtime: Mesa's EGL/GL/OSMesa (llvmpipe), Xvfb for the GLX tests.
# Build: the GL/EGL/OSMesa/GLUT headers for the C examples, pkg-config, a C compiler.
DEB_PACKAGES := libegl1 libegl-mesa0 libgl1 libgl1-mesa-dri libglx-mesa0 libosmesa6 \
                libgl-dev libegl-dev libosmesa6-dev freeglut3-dev libx11-dev \
                xvfb x11-apps x11-utils xauth pkg-config gcc make

.PHONY: all deps build header examples demo test lint bench clean

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

build: deps
	$(CARGO) build $(CARGO_PROFILE_FLAG)
	@ln -sf libglstereo.so $(LIBDIR)/libglstereo.so.0

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
	$(CARGO) clippy $(CARGO_PROFILE_FLAG) --all-targets -- -D warnings

test: deps lint
	$(CARGO) test $(CARGO_PROFILE_FLAG) --no-fail-fast

# Benchmarks (release build; see BENCHMARKS.md): the frame loop, mono vs
# stereo on EGL, OSMesa and GLX (a private Xvfb), light and heavy scenes;
# the same with both eyes captured to PNG every frame; then every output
# mode's CPU and GL composition against a memcpy (criterion).
bench:
	$(CARGO) bench --bench frame_loop
	$(CARGO) bench --bench frame_loop -- --scene light --capture --no-control
	$(CARGO) bench --bench compose

clean:
	$(CARGO) clean
	$(MAKE) -C c-examples clean
	rm -rf $(OUT)
