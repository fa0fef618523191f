// Placeholder so the target exists before its issue lands; remove when real sources arrive.
