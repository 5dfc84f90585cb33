"""Reference solutions that tests and reports share, none of them our own
elements: closed forms and ODE solutions (elastica, rigid pendulum, beam
theory), published tables (seed_tables), signal analysis (pencil)."""
