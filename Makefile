# artiplan: two commands on a fresh machine: `make demo` and `make test`.
PY ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed
# Headless rendering for MuJoCo (EGL via Mesa; OSMesa as fallback, see scripts/setup-system.sh).
export MUJOCO_GL ?= egl

.PHONY: setup bytecode system demo test lint typecheck check clean

setup: $(STAMP)

$(STAMP): pyproject.toml scripts/setup-system.sh
	bash scripts/setup-system.sh
	$(PY) -m venv $(VENV)
	$(BIN)/pip install -q --upgrade pip
	$(BIN)/pip install -q -e '.[dev,up]'
	# robosuite only for its Baxter MJCF assets: never let pip resolve its dependencies.
	$(BIN)/pip install -q --no-deps 'robosuite==1.5.2'
	touch $(STAMP)

# Bytecode for src even where PYTHONDONTWRITEBYTECODE is set (as on these machines): without
# it every artiplan process compiles its ~130 modules again (0.36 s instead of 0.15 s).
bytecode: $(STAMP)
	$(BIN)/python -m compileall -q src

demo: setup bytecode
	$(BIN)/artiplan demo -o demo-out

test: setup bytecode
	$(BIN)/python -m pytest -q -m "not slow or ci" --timeout=600

test-all: setup
	$(BIN)/python -m pytest -q --timeout=1800

lint: setup
	$(BIN)/ruff check src tests
	$(BIN)/ruff format --check src tests || true

typecheck: setup
	$(BIN)/mypy

check: lint typecheck test

clean:
	rm -rf $(VENV) demo-out .pytest_cache .mypy_cache .ruff_cache
