"""The topology stage: start points on every component (interval search of the level g = F_Q o P), the meridians of
tangency, and starts rescued where a search's start was lost."""
