(define (problem lander-07)
  (:domain lander)
  (:init
    (flying)
    (= (h) 2046.3) (= (v) -50)
    (= (mass) 1115.65) (= (fuel) 115.65) (= (burn-rate) 5)
    (= (gravity) 3.71) (= (thrust) 9519.8)
    (= (touch-height) 1) (= (safe-speed) 1.2))
  (:goal (and (landed))))
