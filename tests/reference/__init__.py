"""Independent references for the tests (no hypercontact code inside)."""
